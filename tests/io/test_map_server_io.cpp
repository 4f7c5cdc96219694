#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/map_server_io.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

TEST(MapServer, RoundTripKeepsLethalFreeAndUnknown) {
    const auto dir = testing_util::fresh_dir("map");
    Costmap m({-2.0, 1.5}, 0.1, 30, 20);
    m.at(3, 4) = cost::kLethal;
    m.at(29, 19) = cost::kUnknown;
    m.at(10, 2) =
        100;  // soft: exported in scale mode, read back as free (below free_thresh) or unknown
    write_map_server(dir / "map.yaml", m);
    EXPECT_TRUE(std::filesystem::exists(dir / "map.pgm"));
    const Costmap back = read_map_server(dir / "map.yaml");
    EXPECT_EQ(back.width, 30);
    EXPECT_EQ(back.height, 20);
    EXPECT_EQ(back.origin_m, m.origin_m);
    EXPECT_EQ(back.resolution_m, 0.1);
    EXPECT_EQ(back.at(3, 4), cost::kLethal);
    EXPECT_EQ(back.at(29, 19), cost::kUnknown);
    EXPECT_EQ(back.at(0, 0), cost::kFree);
    EXPECT_EQ(back.at(10, 2), cost::kUnknown);  // occupancy 100/254 lies between the thresholds
}

TEST(MapServer, BadFilesNameTheFileAndProblem) {
    const auto dir = testing_util::fresh_dir("bad");
    std::ofstream(dir / "a.yaml") << "image: a.pgm\nresolution: -1\norigin: [0, 0]\n";
    try {
        read_map_server(dir / "a.yaml");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("resolution must be in"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("origin must be"), std::string::npos) << e.what();
    }
    std::ofstream(dir / "b.yaml") << "image: b.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
    std::ofstream(dir / "b.pgm") << "P5\n4 4\n255\nabc";
    try {
        read_map_server(dir / "b.yaml");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_EQ(
            std::string(e.what()),
            (dir / "b.pgm").string() + ": PGM data size mismatch: 4 x 4 needs 16 bytes, found 3");
    }
    EXPECT_THROW(parse_pgm("P2\n1 1\n255\n0"), FormatError);
    EXPECT_THROW(parse_pgm("P5\n1 1\n65535\nab"), FormatError);
    EXPECT_EQ(parse_pgm("P5 # comment\n2 1\n255\nab").pixels, "ab");
}

}  // namespace
}  // namespace makeway::io
