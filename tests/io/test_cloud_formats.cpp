#include <gtest/gtest.h>

#include "io/error.hpp"
#include "io/kitti_bin.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "io/point_cloud_io.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

using testing_util::clouds_bit_equal;
using testing_util::random_cloud;

const PointFields kXyzOnly{};
const PointFields kXyzI{.intensity = true};
const PointFields kXyzLabel{.label = true, .instance = true};

std::string pcd_encoding_name(const ::testing::TestParamInfo<PcdEncoding>& p) {
    return p.param == PcdEncoding::kAscii    ? "ascii"
           : p.param == PcdEncoding::kBinary ? "binary"
                                             : "compressed";
}

std::string ply_encoding_name(const ::testing::TestParamInfo<PlyEncoding>& p) {
    return p.param == PlyEncoding::kAscii ? "ascii" : "binary";
}

class PcdRoundTrip : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdRoundTrip, EveryChannelBitForBit) {
    for (const PointFields& f : {PointFields::all(), kXyzOnly, kXyzI, kXyzLabel}) {
        const PointCloud c = random_cloud(1, 2000, f);
        const CloudFile back = parse_pcd(serialize_pcd(c, GetParam()));
        EXPECT_TRUE(clouds_bit_equal(c, back.cloud));
        EXPECT_TRUE(back.info.ignored_fields.empty());
    }
}

TEST_P(PcdRoundTrip, EmptyCloud) {
    const CloudFile back = parse_pcd(serialize_pcd(PointCloud{}, GetParam()));
    EXPECT_EQ(back.cloud.size(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdRoundTrip,
                         ::testing::Values(PcdEncoding::kAscii, PcdEncoding::kBinary,
                                           PcdEncoding::kBinaryCompressed),
                         pcd_encoding_name);

class PlyRoundTrip : public ::testing::TestWithParam<PlyEncoding> {};

TEST_P(PlyRoundTrip, EveryChannelBitForBit) {
    for (const PointFields& f : {PointFields::all(), kXyzOnly, kXyzI, kXyzLabel}) {
        const PointCloud c = random_cloud(2, 2000, f);
        EXPECT_TRUE(clouds_bit_equal(c, parse_ply(serialize_ply(c, GetParam())).cloud));
    }
}

INSTANTIATE_TEST_SUITE_P(Encodings, PlyRoundTrip,
                         ::testing::Values(PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian),
                         ply_encoding_name);

TEST(KittiBin, RoundTripXyzIntensity) {
    const PointCloud c = random_cloud(3, 1000, kXyzI);
    EXPECT_TRUE(clouds_bit_equal(c, parse_kitti_bin(serialize_kitti_bin(c)).cloud));
}

// Through files, across formats and encodings: PCD -> PLY -> KITTI -> PCD ... keeps every value
// that both ends of each hop can hold.
TEST(CrossFormat, ChainOfFilesKeepsEveryValue) {
    const auto dir = testing_util::fresh_dir("chain");
    const PointCloud full = random_cloud(4, 3000, PointFields::all());
    const std::vector<std::pair<std::string, CloudWriteOptions>> hops = {
        {"a.pcd", {.pcd = PcdEncoding::kBinaryCompressed}},
        {"b.ply", {.ply = PlyEncoding::kAscii}},
        {"c.pcd", {.pcd = PcdEncoding::kAscii}},
        {"d.ply", {.ply = PlyEncoding::kBinaryLittleEndian}},
        {"e.pcd", {.pcd = PcdEncoding::kBinary}},
    };
    PointCloud current = full;
    for (const auto& [name, options] : hops) {
        EXPECT_TRUE(write_point_cloud(dir / name, current, options).empty());
        current = read_point_cloud(dir / name).cloud;
        EXPECT_TRUE(clouds_bit_equal(full, current)) << name;
    }
    // KITTI keeps x y z intensity and reports the rest as dropped.
    const auto dropped = write_point_cloud(dir / "f.bin", current);
    EXPECT_EQ(dropped, (std::vector<std::string>{"ring", "time", "label", "instance"}));
    PointCloud xyzi = full;
    xyzi.resize(0, {});
    xyzi.xyz = full.xyz;
    xyzi.intensity = full.intensity;
    const PointCloud from_bin = read_point_cloud(dir / "f.bin").cloud;
    EXPECT_TRUE(clouds_bit_equal(xyzi, from_bin));
    write_point_cloud(dir / "g.ply", from_bin, {.ply = PlyEncoding::kAscii});
    write_point_cloud(dir / "h.pcd", read_point_cloud(dir / "g.ply").cloud);
    write_point_cloud(dir / "i.bin", read_point_cloud(dir / "h.pcd").cloud);
    EXPECT_TRUE(clouds_bit_equal(xyzi, read_point_cloud(dir / "i.bin").cloud));
}

TEST(PcdForeign, PclStyleFileWithExtraFieldsAndDoubles) {
    // As written by other tools: an rgb field, x/y/z as doubles, an organised 2 x 2 cloud,
    // time under the alias "t", ring as a signed 16-bit integer.
    const std::string text =
        "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z rgb t ring normal\nSIZE 8 8 8 4 4 2 4\n"
        "TYPE F F F U F I F\nCOUNT 1 1 1 1 1 1 3\nWIDTH 2\nHEIGHT 2\n"
        "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
        "1.5 2 3 255 0.01 5 0 0 1\n4 5 6 0 0.02 6 0 0 1\nnan nan nan 0 0 0 0 0 1\n"
        "-1 -2 -3 7 0.03 31 0 0 1\n";
    const CloudFile f = parse_pcd(text);
    EXPECT_EQ(f.cloud.size(), 4u);
    EXPECT_EQ(f.info.ignored_fields, (std::vector<std::string>{"rgb", "normal"}));
    EXPECT_EQ(f.cloud.fields(), (PointFields{.ring = true, .time = true}));
    EXPECT_EQ(f.cloud.xyz[0], Eigen::Vector3f(1.5f, 2, 3));
    EXPECT_EQ(f.cloud.ring[3], 31);
    EXPECT_FLOAT_EQ(f.cloud.time_s[1], 0.02f);
    EXPECT_EQ(f.cloud.count_non_finite(), 1u);
}

TEST(PlyForeign, FacesListsAndBigEndian) {
    // A mesh-style PLY: a list property in the vertex element and a face element after it.
    const std::string ascii =
        "ply\nformat ascii 1.0\ncomment from elsewhere\nelement vertex 3\nproperty double x\n"
        "property double y\nproperty double z\nproperty uchar red\nproperty list uchar int idx\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0 255 2 1 2\n1 0 0 0 0\n0 1 0 10 1 9\n3 0 1 2\n";
    const CloudFile a = parse_ply(ascii);
    EXPECT_EQ(a.cloud.size(), 3u);
    EXPECT_EQ(a.cloud.xyz[2], Eigen::Vector3f(0, 1, 0));
    EXPECT_EQ(a.info.ignored_fields, (std::vector<std::string>{"red", "idx"}));

    std::string be =
        "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nproperty ushort ring\nend_header\n";
    const unsigned char data[] = {0x3f, 0x80, 0, 0, 0x40, 0, 0, 0, 0xc0, 0x40, 0, 0, 0x01, 0x02};
    be.append(reinterpret_cast<const char*>(data), sizeof(data));
    const CloudFile b = parse_ply(be);
    EXPECT_EQ(b.cloud.xyz[0], Eigen::Vector3f(1, 2, -3));
    EXPECT_EQ(b.cloud.ring[0], 0x0102);
}

TEST(CloudFiles, NonFinitePolicies) {
    const auto dir = testing_util::fresh_dir("nan");
    PointCloud c = random_cloud(5, 10, kXyzI);
    c.xyz[4].y() = std::numeric_limits<float>::quiet_NaN();
    c.xyz[7].z() = std::numeric_limits<float>::infinity();
    write_point_cloud(dir / "n.pcd", c);
    EXPECT_EQ(read_point_cloud(dir / "n.pcd", {.non_finite = NonFinitePolicy::kKeep}).cloud.size(),
              10u);
    EXPECT_EQ(read_point_cloud(dir / "n.pcd", {.non_finite = NonFinitePolicy::kDrop}).cloud.size(),
              8u);
    try {
        read_point_cloud(dir / "n.pcd");
        FAIL() << "NaN points accepted";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "2 points have NaN or infinite coordinates (first at index 4)"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace makeway::io
