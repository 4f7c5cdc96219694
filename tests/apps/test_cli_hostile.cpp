// Boundary cases from the hardening probe (issue 14): one line, exit 2, no output; and the
// output side (a full standard output is not a success).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

TEST(Cli, HostileInputsAtTheBoundary) {
    const auto dir = testing_util::fresh_dir("hostile");
    // A PCD whose field name is not ASCII (an encoding fault of the file; was exit 1, internal
    // error).
    std::ofstream(dir / "utf.pcd")
        << "VERSION .7\nFIELDS x y z \xff\xfe\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
           "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n";
    // A cloud of NaN points only, converted with --non-finite drop (was a 0-byte .bin).
    PointCloud nan_cloud = testing_util::random_cloud(5, 3, {});
    for (auto& p : nan_cloud.xyz) p.x() = NAN;
    io::write_point_cloud(dir / "allnan.bin", nan_cloud);
    // map_server keys out of their domain (was accepted; the robot never moved).
    std::ofstream(dir / "map.pgm") << "P2\n2 2\n255\n0 255\n255 0\n";
    std::ofstream(dir / "bogus_mode.yaml")
        << "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: bogus\n";
    std::ofstream(dir / "negate.yaml")
        << "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 2\n";
    std::ofstream(dir / "fine.yaml") << "image: map.pgm\nresolution: 0.00001\norigin: [0, 0, 0]\n";
    // A pillar of negative size (walls were already checked).
    std::ofstream(dir / "good.yaml") << "name: empty\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n";
    std::ofstream(dir / "pillar.yaml") << "name: p\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
                                          "pillars:\n  - {centre_m: [1, 1], size_m: [-0.4, 0.4]}\n";
    // Scenes beyond any room (they stalled): a 1000 km floor, 10001 walls.
    std::ofstream(dir / "huge.yaml")
        << "name: h\nfloor: {min_m: [-500000, -5], max_m: [500000, 5]}\n";
    {
        std::ofstream walls(dir / "walls.yaml");
        walls << "name: w\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\nwalls:\n";
        for (int i = 0; i <= 10000; ++i) walls << "  - {a_m: [0, 0], b_m: [1, 0]}\n";
    }
    // A wall 2000 km long on a 10 m floor (the simulator allocated until bad_alloc; issue 34).
    std::ofstream(dir / "long_wall.yaml") << "name: l\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
                                             "walls:\n  - {a_m: [0, 0], b_m: [2000000, 0]}\n";
    // A FIFO as input (blocked forever waiting for a writer).
    ASSERT_EQ(mkfifo((dir / "pipe.pcd").c_str(), 0600), 0);
    // Detection frames whose stamps go back in time (the progress bar's line came before the
    // error).
    std::filesystem::create_directories(dir / "dets");
    std::ofstream(dir / "dets" / "000000.json") << "{\"stamp_s\": 1.0, \"detections\": []}";
    std::ofstream(dir / "dets" / "000001.json") << "{\"stamp_s\": 0.5, \"detections\": []}";
    // A scene whose mesh lies outside its folder (was read from anywhere).
    std::filesystem::create_directories(dir / "room");
    std::ofstream(dir / "room" / "escape.yaml")
        << "name: e\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
           "objects:\n  - {id: 1, class: chair, mesh: ../../x.obj}\n";
    // Outputs in the way: a folder where navigate's picture and scene's third session go.
    std::filesystem::create_directories(dir / "o9" / "route.png");
    std::filesystem::create_directories(dir / "o10" / "s_session2.png");
    // Labelling sessions whose --odometry-name is a folder (was ignored: the sessions ran without
    // odometry; issue 34).
    std::filesystem::create_directories(dir / "s1" / "clouds");
    std::filesystem::create_directories(dir / "s1" / "odo");
    std::filesystem::create_directories(dir / "s2" / "clouds");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"simulate --scene " + (dir / "good.yaml").string() + " --frames 1000000 --out " +
             (dir / "o11").string(),
         "1000000 frames of 32 beams x 1800 columns need about"},  // 1.7 TB: refused before
                                                                   // starting
        {"simulate --scene " + (dir / "room" / "escape.yaml").string() + " --out " +
             (dir / "o12").string(),
         "mesh '../../x.obj' is outside the scene's folder (--allow-outside-paths to read it)"},
        {"navigate --scene " + (dir / "good.yaml").string() + " --time-limit 2 --out " +
             (dir / "o9").string(),
         (dir / "o9" / "route.png").string() + ": in the way of an output"},
        {"scene --sessions 3 --out " + (dir / "o10" / "s.yaml").string(),
         (dir / "o10" / "s_session2.png").string() + ": in the way"},
        {"track --detections " + (dir / "dets").string() + " --out " + (dir / "o6").string(),
         (dir / "dets" / "000001.json").string() + ": stamp_s goes back in time"},
        {"simulate --scene " + (dir / "huge.yaml").string() + " --out " + (dir / "o7").string(),
         "floor: at most 200 m on a side"},
        {"simulate --scene " + (dir / "walls.yaml").string() + " --out " + (dir / "o8").string(),
         "at most 10000 walls"},
        {"simulate --scene " + (dir / "long_wall.yaml").string() + " --out " +
             (dir / "o14").string(),
         "wall: an end lies more than 10 m beyond the floor"},
        {"info " + (dir / "pipe.pcd").string(),
         (dir / "pipe.pcd").string() + ": not a regular file"},
        {"info " + (dir / "utf.pcd").string(),
         (dir / "utf.pcd").string() + ": header FIELDS: field 4 is not a printable ASCII name"},
        {"convert " + (dir / "allnan.bin").string() + " " + (dir / "o1.bin").string() +
             " --non-finite drop",
         (dir / "allnan.bin").string() + ": no finite points left to convert"},
        {"navigate --scene " + (dir / "good.yaml").string() + " --map " +
             (dir / "bogus_mode.yaml").string() + " --out " + (dir / "o2").string(),
         "mode must be trinary, scale or raw"},
        {"navigate --scene " + (dir / "good.yaml").string() + " --map " +
             (dir / "negate.yaml").string() + " --out " + (dir / "o3").string(),
         "negate must be 0 or 1"},
        {"navigate --scene " + (dir / "good.yaml").string() + " --map " +
             (dir / "fine.yaml").string() + " --out " + (dir / "o4").string(),
         "resolution must be in [0.001, 100)"},
        {"simulate --scene " + (dir / "pillar.yaml").string() + " --out " + (dir / "o5").string(),
         "pillar: size_m and height_m must be > 0"},
        // A sensor 1e30 m away (the shape completion integrated rays from it forever; issue 34).
        {"complete --cloud " + (dir / "allnan.bin").string() +
             " --box 0,0,0.5,0.5,0.5,1,0 --class chair --sensor 1e30,0,0 --out " +
             (dir / "o13.obj").string(),
         "--sensor: lies 1e+30 m from the box (a LiDAR sees at most 200 m)"},
        {"complete --cloud " + (dir / "allnan.bin").string() +
             " --box 0,0,0.5,50,0.5,1,0 --class chair --out " + (dir / "o13.obj").string(),
         "--box: length, width and height must be at most 10 m (furniture)"},
        {"label --sessions " + (dir / "s1").string() + " " + (dir / "s2").string() +
             " --odometry-name odo --out " + (dir / "o15").string(),
         (dir / "s1" / "odo").string() + ": is not a file: --odometry-name"},
    };
    for (const auto& [args, expected] : cases) {
        const CliRun r = run_makeway(args, dir);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
        EXPECT_EQ(lines(r.err), 1u) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    }
    for (const char* out : {"o1.bin", "o2", "o3", "o4", "o5", "o6", "o7", "o8", "o11", "o12",
                            "o13.obj", "o14", "o15"}) {
        EXPECT_FALSE(std::filesystem::exists(dir / out)) << out;
    }
    // Where an output was in the way, nothing else was delivered beside it.
    const auto entries = [](const std::filesystem::path& d) {
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(d))
            names.push_back(e.path().filename().string());
        return names;
    };
    EXPECT_EQ(entries(dir / "o9"), std::vector<std::string>{"route.png"});
    EXPECT_EQ(entries(dir / "o10"), std::vector<std::string>{"s_session2.png"});
    // Standard output on a full device: exit 2 and one line, not a silent success.
    const int rc =
        std::system((std::string(MAKEWAY_BIN) + " scene --out " + (dir / "s.yaml").string() +
                     " > /dev/full 2> " + (dir / "err.txt").string())
                        .c_str());
    EXPECT_EQ(WEXITSTATUS(rc), 2);
    std::ifstream err(dir / "err.txt");
    const std::string line((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
    EXPECT_NE(line.find("makeway: standard output: write failed"), std::string::npos) << line;
}

}  // namespace
}  // namespace makeway
