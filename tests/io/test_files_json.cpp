#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/top_down_png.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

TEST(JsonIo, BoxRoundTripAndErrors) {
    const auto dir = testing_util::fresh_dir("json");
    const OrientedBox b{{1, 2, 0.4}, {0.5, 0.6, 0.9}, -1.25};
    write_json(dir / "b.json", {{"box", to_json(b)}});
    const OrientedBox back = box_from_json(read_json(dir / "b.json")["box"]);
    EXPECT_EQ(back.centre_m, b.centre_m);
    EXPECT_EQ(back.size_m, b.size_m);
    EXPECT_EQ(back.yaw_rad, b.yaw_rad);
    EXPECT_THROW(box_from_json(Json{{"centre_m", {1, 2}}}), FormatError);
    EXPECT_THROW(
        box_from_json(Json{{"centre_m", {1, 2, 3}}, {"size_m", {1, -1, 1}}, {"yaw_rad", 0}}),
        FormatError);
    std::ofstream(dir / "bad.json") << "{\"a\": [1, 2";
    try {
        read_json(dir / "bad.json");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos);
    }
}

TEST(TopDownPng, WritesAPngOfTheExpectedSize) {
    const auto dir = testing_util::fresh_dir("png");
    PointCloud c;
    c.xyz = {{0, 0, 0}, {4, 2, 1}};
    write_top_down_png(dir / "t.png", c, {}, {.pixels_per_m = 10.0, .margin_m = 1.0});
    std::ifstream in(dir / "t.png", std::ios::binary);
    std::string head(24, '\0');
    in.read(head.data(), 24);
    EXPECT_EQ(head.substr(1, 3), "PNG");
    auto be32 = [&](int off) {
        return (static_cast<unsigned char>(head[off]) << 24) |
               (static_cast<unsigned char>(head[off + 1]) << 16) |
               (static_cast<unsigned char>(head[off + 2]) << 8) |
               static_cast<unsigned char>(head[off + 3]);
    };
    EXPECT_EQ(be32(16), 64u);  // (4 + 2 margins) * 10 px/m = 60 -> at least 64
    EXPECT_EQ(be32(20), 64u);
}

// Width and height of a PNG file (its IHDR).
std::pair<unsigned, unsigned> png_size(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[24] = {};
    in.read(reinterpret_cast<char*>(head), 24);
    const auto be32 = [&](int off) {
        return (unsigned{head[off]} << 24) | (unsigned{head[off + 1]} << 16) |
               (unsigned{head[off + 2]} << 8) | unsigned{head[off + 3]};
    };
    return {be32(16), be32(20)};
}

// The picture covers the points within the detector's reach and every box: a point 50 m away
// does not shrink it to a dot, a box past the points widens it.
TEST(TopDownPng, DetectionsPictureCoversTheReachAndTheBoxes) {
    const auto dir = testing_util::fresh_dir("png_dets");
    PointCloud raw, kept;
    raw.xyz = {{-3, -2, 0.0}, {3, 2, 0.5}, {50, 0, 0.5}};
    kept.xyz = {{3, 2, 0.5}};
    write_detections_png(dir / "a.png", raw, kept, {}, 8.0, "no detections");
    // [-3, 3] x [-2, 2] plus 1 m margins at 60 px/m.
    EXPECT_EQ(png_size(dir / "a.png"), std::make_pair(480u, 360u));
    Detection d;
    d.box_sensor.centre_m = {4.0, 0.0, 0.5};
    d.box_sensor.size_m = {1.0, 1.0, 1.0};
    d.score = 0.5;
    write_detections_png(dir / "b.png", raw, kept, {d}, 8.0, "one chair");
    EXPECT_EQ(png_size(dir / "b.png"), std::make_pair(570u, 360u));  // x up to 4.5 m
}

}  // namespace
}  // namespace makeway::io
