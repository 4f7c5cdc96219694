// PointCloud2 layouts of real drivers (Velodyne, Ouster, Hesai) and malformed ones, the costmap's
// OccupancyGrid mapping, markers, and bags written then read back.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "io/error.hpp"
#include "lying_message.hpp"
#include "ros/bag_check.hpp"
#include "ros/bag_io.hpp"
#include "ros/msg_conversions.hpp"

namespace makeway::rosio {
namespace {

using sensor_msgs::PointField;

PointField field(const std::string& name, std::uint32_t offset, std::uint8_t type) {
    PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = type;
    f.count = 1;
    return f;
}

template <typename T>
void put(sensor_msgs::PointCloud2& m, std::size_t point, std::uint32_t offset, T v) {
    std::memcpy(m.data.data() + point * m.point_step + offset, &v, sizeof(T));
}

std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("makeway_test_ros_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

PointCloud sample_cloud() {
    PointCloud c;
    PointFields f;
    f.intensity = f.ring = f.time = true;
    c.resize(3, f);
    c.xyz = {{1.0f, 2.0f, 0.5f}, {-3.25f, 0.125f, 1.5f}, {10.0f, -4.0f, -0.25f}};
    c.intensity = {10.0f, 55.5f, 200.0f};
    c.ring = {0, 17, 31};
    c.time_s = {0.0f, 0.05f, 0.0999f};
    return c;
}

TEST(PointCloud2, VelodyneLayoutRoundTrips) {
    const PointCloud c = sample_cloud();
    const sensor_msgs::PointCloud2 msg = to_point_cloud2(c, 1767225600.25, "velodyne");
    EXPECT_EQ(msg.point_step, 22u);
    const CloudSweep s = from_point_cloud2(msg);
    ASSERT_EQ(s.points.size(), 3u);
    EXPECT_TRUE(s.timed);
    EXPECT_EQ(s.time_field, "time");
    EXPECT_EQ(s.frame_id, "velodyne");
    EXPECT_NEAR(s.stamp_s, 1767225600.25, 1e-6);
    EXPECT_NEAR(s.duration_s, 0.0999, 1e-6);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(s.points.xyz[i], c.xyz[i]);
        EXPECT_EQ(s.points.intensity[i], c.intensity[i]);
        EXPECT_EQ(s.points.ring[i], c.ring[i]);
        EXPECT_NEAR(s.points.time_s[i], c.time_s[i], 1e-6);
    }
}

TEST(PointCloud2, VelodyneTimesBeforeTheStampStartTheSweepAtTheFirstPoint) {
    // Some Velodyne drivers stamp the sweep's end: times run from -0.1 to 0.
    PointCloud c = sample_cloud();
    c.time_s = {-0.1f, -0.05f, 0.0f};
    const CloudSweep s = from_point_cloud2(to_point_cloud2(c, 1000.0, "velodyne"));
    EXPECT_NEAR(s.stamp_s, 999.9, 1e-6);
    EXPECT_NEAR(s.points.time_s[0], 0.0, 1e-6);
    EXPECT_NEAR(s.points.time_s[2], 0.1, 1e-6);
}

TEST(PointCloud2, OusterLayoutWithNanosecondsAndPadding) {
    // ouster_ros: x y z (float32) + 4 bytes padding, intensity float32, t uint32 ns, reflectivity
    // uint16, ring uint8 (older drivers), noise uint16, range uint32; point_step 48; organised 2
    // x 2.
    sensor_msgs::PointCloud2 m;
    m.header.stamp = ros::Time(500.0);
    m.header.frame_id = "os_sensor";
    m.height = 2;
    m.width = 2;
    m.fields = {
        field("x", 0, PointField::FLOAT32),    field("y", 4, PointField::FLOAT32),
        field("z", 8, PointField::FLOAT32),    field("intensity", 16, PointField::FLOAT32),
        field("t", 20, PointField::UINT32),    field("reflectivity", 24, PointField::UINT16),
        field("ring", 26, PointField::UINT8),  field("noise", 28, PointField::UINT16),
        field("range", 32, PointField::UINT32)};
    m.point_step = 48;
    m.row_step = 96;
    m.data.assign(192, 0);
    for (std::size_t i = 0; i < 4; ++i) {
        put<float>(m, i, 0, 1.0f + static_cast<float>(i));
        put<float>(m, i, 4, 2.0f);
        put<float>(m, i, 8, 0.5f);
        put<float>(m, i, 16, 100.0f);
        put<std::uint32_t>(m, i, 20,
                           static_cast<std::uint32_t>(25'000'000 * i));  // 0, 25, 50, 75 ms
        put<std::uint8_t>(m, i, 26, static_cast<std::uint8_t>(60 + i));
    }
    const CloudSweep s = from_point_cloud2(m);
    ASSERT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.time_field, "t");
    EXPECT_NEAR(s.stamp_s, 500.0, 1e-9);
    EXPECT_NEAR(s.duration_s, 0.075, 1e-9);
    EXPECT_NEAR(s.points.time_s[3], 0.075, 1e-6);
    EXPECT_EQ(s.points.ring[2], 62);
    EXPECT_EQ(s.points.xyz[3].x(), 4.0f);
}

TEST(PointCloud2, HesaiLayoutWithAbsoluteTimestamps) {
    // hesai_lidar: x y z intensity (float32), timestamp (float64, absolute s), ring (uint16).
    sensor_msgs::PointCloud2 m;
    m.header.stamp = ros::Time(1700000000.5);  // Hesai stamps the sweep's end
    m.height = 1;
    m.width = 3;
    m.fields = {
        field("x", 0, PointField::FLOAT32),          field("y", 4, PointField::FLOAT32),
        field("z", 8, PointField::FLOAT32),          field("intensity", 12, PointField::FLOAT32),
        field("timestamp", 16, PointField::FLOAT64), field("ring", 24, PointField::UINT16)};
    m.point_step = 26;
    m.row_step = 78;
    m.data.assign(78, 0);
    for (std::size_t i = 0; i < 3; ++i) {
        put<float>(m, i, 0, 1.0f);
        put<double>(m, i, 16, 1700000000.4 + 0.05 * static_cast<double>(i));
    }
    const CloudSweep s = from_point_cloud2(m);
    EXPECT_EQ(s.time_field, "timestamp");
    EXPECT_NEAR(s.stamp_s, 1700000000.4, 1e-6);
    EXPECT_NEAR(s.duration_s, 0.1, 1e-6);
    EXPECT_NEAR(s.points.time_s[1], 0.05, 1e-6);
}

TEST(PointCloud2, WithoutATimeFieldTheSweepIsInstantaneousAtItsStamp) {
    sensor_msgs::PointCloud2 m = to_point_cloud2(sample_cloud(), 42.0, "lidar");
    m.fields.resize(3);  // x y z only; the rest of each point is padding
    const CloudSweep s = from_point_cloud2(m);
    EXPECT_FALSE(s.timed);
    EXPECT_TRUE(s.points.time_s.empty());
    EXPECT_TRUE(s.points.intensity.empty());
    EXPECT_NEAR(s.stamp_s, 42.0, 1e-9);
}

TEST(PointCloud2, MalformedMessagesAreFormatErrorsThatSayWhy) {
    const sensor_msgs::PointCloud2 good = to_point_cloud2(sample_cloud(), 1.0, "v");
    const auto expect_error = [](const sensor_msgs::PointCloud2& m, const std::string& part) {
        try {
            from_point_cloud2(m);
            ADD_FAILURE() << "no error, expected: " << part;
        } catch (const io::FormatError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    sensor_msgs::PointCloud2 m = good;
    m.is_bigendian = true;
    expect_error(m, "big-endian");
    m = good;
    m.data.resize(m.data.size() - 1);
    expect_error(m, "data holds");
    m = good;
    m.fields[5].offset = 20;  // time (4 bytes) past the 22-byte point
    expect_error(m, "outside the point");
    m = good;
    m.fields.erase(m.fields.begin() + 2);  // no z
    expect_error(m, "no x, y and z");
    m = good;
    m.fields[3].datatype = 9;
    expect_error(m, "unknown datatype");
    m = good;
    m.row_step = 5;
    expect_error(m, "row_step");
    m = good;
    m.fields[0].datatype = PointField::UINT8;
    expect_error(m, "float32 or float64");
    m = good;
    m.width = 1000000;  // more points than data
    m.row_step = m.width * m.point_step;
    expect_error(m, "data holds");
}

TEST(OccupancyGrid, CostsMapAsNav2PublishesThem) {
    EXPECT_EQ(occupancy_of_cost(cost::kFree), 0);
    EXPECT_EQ(occupancy_of_cost(1), 1);
    EXPECT_EQ(occupancy_of_cost(252), 98);
    EXPECT_EQ(occupancy_of_cost(128), 1 + 97 * 127 / 251);
    EXPECT_EQ(occupancy_of_cost(cost::kInscribed), 99);
    EXPECT_EQ(occupancy_of_cost(cost::kLethal), 100);
    EXPECT_EQ(occupancy_of_cost(cost::kUnknown), -1);
    Costmap c({-1.0, 2.0}, 0.1, 3, 2);
    c.at(2, 1) = cost::kLethal;
    const nav_msgs::OccupancyGrid g = to_occupancy_grid(c, 10.0, "map");
    EXPECT_EQ(g.info.width, 3u);
    EXPECT_EQ(g.info.height, 2u);
    EXPECT_DOUBLE_EQ(g.info.origin.position.x, -1.0);
    EXPECT_DOUBLE_EQ(g.info.origin.position.y, 2.0);
    EXPECT_EQ(g.data[5], 100);  // row 1, column 2: row-major from the origin, as the costmap
    EXPECT_EQ(g.data[0], 0);
}

TEST(Markers, BoxesLabelsAndZonesAfterADeleteAll) {
    ObjectEstimate chair;
    chair.id = 7;
    chair.box_world = OrientedBox{{1.0, 2.0, 0.45}, {0.5, 0.5, 0.9}, 0.3};
    chair.existence = 0.9;
    ObjectEstimate unsure = chair;
    unsure.id = 8;
    unsure.existence = 0.1;  // below min_existence: no zone
    const costmap::AffordanceParams zones;
    const auto a = to_markers({chair, unsure}, zones, 5.0, "map");
    ASSERT_EQ(a.markers.size(), 1u + 3u + 2u);
    EXPECT_EQ(a.markers[0].action, visualization_msgs::Marker::DELETEALL);
    EXPECT_EQ(a.markers[1].type, visualization_msgs::Marker::CUBE);
    EXPECT_EQ(a.markers[1].id, 7);
    EXPECT_NEAR(a.markers[1].pose.orientation.z, std::sin(0.15), 1e-12);
    EXPECT_EQ(a.markers[2].text, "chair 7 p=0.90");
    EXPECT_EQ(a.markers[3].ns, "zones");
    EXPECT_GT(a.markers[3].points.size(), 10u);
}

TEST(Bag, CloudsAndOdometryWrittenThenReadBack) {
    const auto dir = fresh_dir("bag");
    {
        BagWriter w(dir / "d.bag");
        for (int k = 0; k < 3; ++k) {
            w.write_cloud("/velodyne_points", sample_cloud(), 100.0 + 0.1 * k, "velodyne");
            w.write_odometry("/odom", Pose2{0.1 * k, 0.0, 0.01 * k}, 1.0, 0.0, 100.0 + 0.1 * k,
                             "odom", "base_link");
        }
        w.write_text("/notes", "hello", 100.0);
        EXPECT_FALSE(std::filesystem::exists(dir / "d.bag"));  // still .active
        w.close();
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "d.bag"));
    EXPECT_FALSE(std::filesystem::exists(dir / "d.bag.active"));
    BagReader r(dir / "d.bag", {}, true);
    EXPECT_EQ(r.sweeps(), 3u);
    ASSERT_EQ(r.odometry().size(), 3u);
    EXPECT_NEAR(r.odometry()[2].pose.x_m, 0.2, 1e-12);
    EXPECT_NEAR(r.odometry()[2].pose.yaw_rad, 0.02, 1e-12);
    int n = 0;
    while (auto s = r.next()) {
        EXPECT_NEAR(s->stamp_s, 100.0 + 0.1 * n, 1e-6);
        EXPECT_EQ(s->points.size(), 3u);
        ++n;
    }
    EXPECT_EQ(n, 3);
    // Wrong topics name what the bag has.
    try {
        BagReader bad(dir / "d.bag", {"/points", "/odom"}, false);
        ADD_FAILURE();
    } catch (const io::FileError& e) {
        EXPECT_NE(
            std::string(e.what()).find(
                "no topic /points (sensor_msgs/PointCloud2 topics in the bag: /velodyne_points"),
            std::string::npos)
            << e.what();
    }
    EXPECT_THROW(BagReader(dir / "d.bag", {"/notes", "/odom"}, false),
                 io::FileError);  // a String topic
    EXPECT_THROW(BagReader(dir / "d.bag", {"/velodyne_points", "/wheels"}, true), io::FileError);
    std::ofstream(dir / "not.bag") << "#ROSBAG V2.0\ngarbage";
    EXPECT_THROW(BagReader(dir / "not.bag", {}, false), io::FileError);
    EXPECT_THROW(BagReader(dir / "none.bag", {}, false), io::FileError);
}

TEST(Bag, AWriterDestroyedWithoutCloseLeavesNothing) {
    const auto dir = fresh_dir("bag_abandoned");
    {
        BagWriter w(dir / "x.bag");
        w.write_text("/t", "a", 1.0);
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t u32_at(const std::string& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

void expect_file_error(const std::function<void()>& f, const std::string& part) {
    try {
        f();
        ADD_FAILURE() << "no error, expected: " << part;
    } catch (const io::FileError& e) {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

// The damage a hardening probe found to abort rosbag (its Buffer asserts when a length it trusts
// cannot be allocated): each refused by the walk with the byte it is at, before rosbag reads.
TEST(BagCheck, DamagedStructuresAreRefusedWithTheirByte) {
    const auto dir = fresh_dir("bag_check");
    {
        BagWriter w(dir / "good.bag");
        for (int k = 0; k < 3; ++k)
            w.write_cloud("/velodyne_points", sample_cloud(), 100.0 + 0.1 * k, "velodyne");
        w.close();
    }
    const std::string good = slurp(dir / "good.bag");
    const BagCheckResult ok = check_bag_structure(dir / "good.bag");
    EXPECT_EQ(ok.chunks, 1u);
    EXPECT_EQ(ok.connections, 1u);  // the index's record of the one topic
    // The bag header at byte 13, then the first chunk.
    const std::size_t header_len = u32_at(good, 13);
    const std::size_t chunk = 13 + 4 + header_len + 4 + u32_at(good, 13 + 4 + header_len);
    const std::size_t chunk_header_len = u32_at(good, chunk);
    const std::string chunk_header = good.substr(chunk + 4, chunk_header_len);
    const auto damaged = [&](const std::string& name,
                             const std::function<void(std::string&)>& damage) {
        std::string b = good;
        damage(b);
        std::ofstream(dir / name, std::ios::binary) << b;
        return dir / name;
    };
    const auto put32 = [](std::string& b, std::size_t at, std::uint32_t v) {
        std::memcpy(b.data() + at, &v, 4);
    };
    const auto check = [](const std::filesystem::path& p) {
        return [p] { check_bag_structure(p); };
    };
    expect_file_error(
        check(damaged("header_len.bag", [&](std::string& b) { put32(b, 13, 0xFFFFFFF0u); })),
        "record at byte 13: declares a header of 4294967280 bytes");
    const std::size_t size_field = chunk + 4 + chunk_header.find("size=") + 5;
    expect_file_error(check(damaged("chunk_size.bag",
                                    [&](std::string& b) { put32(b, size_field, 0xFFFFFFF0u); })),
                      "record at byte " + std::to_string(chunk) +
                          " (chunk): declares 4294967280 bytes uncompressed");
    expect_file_error(check(damaged("chunk_data.bag",
                                    [&](std::string& b) {
                                        put32(b, chunk + 4 + chunk_header_len, 0xFFFFFFF0u);
                                    })),
                      "(chunk): declares 4294967280 bytes of data, past the end of the file");
    const std::size_t index_pos =
        13 + 4 + std::string(good.data() + 17, header_len).find("index_pos=") + 10;
    expect_file_error(check(damaged("index_pos.bag",
                                    [&](std::string& b) {
                                        const std::uint64_t into_chunk = chunk + 100;
                                        std::memcpy(b.data() + index_pos, &into_chunk, 8);
                                    })),
                      "index_pos " + std::to_string(chunk + 100) + " is not the start of a record");
    expect_file_error(check(damaged("scrambled.bag",
                                    [&](std::string& b) {
                                        for (std::size_t i = chunk; i < chunk + 12; ++i)
                                            b[i] = static_cast<char>(0xA5 ^ i);
                                    })),
                      "record at byte " + std::to_string(chunk));
    expect_file_error(check(damaged("cut.bag", [&](std::string& b) { b.resize(chunk + 200); })),
                      "past the end of the file");
    expect_file_error(
        check(damaged("v12.bag", [&](std::string& b) { b.replace(0, 13, "#ROSBAG V1.2\n"); })),
        "bag format 1.2 is not supported");
    expect_file_error(check(damaged("text.bag", [&](std::string& b) { b = "hello"; })),
                      "not a ROS 1 bag");
    std::filesystem::create_directories(dir / "folder.bag");
    expect_file_error(check(dir / "folder.bag"), "is a folder, not a bag file");
    ASSERT_EQ(mkfifo((dir / "fifo.bag").c_str(), 0600), 0);
    expect_file_error(check(dir / "fifo.bag"), "is not a regular file");
    expect_file_error(check(dir / "missing.bag"), "no such bag file");
    // The reader walks first: the same damage is the same one line, not rosbag's abort.
    expect_file_error([&] { BagReader r(dir / "header_len.bag", {}, false); },
                      "declares a header of 4294967280 bytes");
}

// Compressed chunks are inflated and walked as uncompressed ones are: rosbag trusts the lengths
// inside them as much as those outside.
TEST(BagCheck, CompressedChunksAreInflatedAndWalked) {
    const auto dir = fresh_dir("bag_check_compressed");
    BagCheckParams no_walk;  // the last pass's walk: compressed chunks skipped
    no_walk.walk_compressed = false;
    for (const auto& [name, kind] :
         {std::pair{"bz2", rosbag::compression::BZ2}, std::pair{"lz4", rosbag::compression::LZ4}}) {
        {
            rosbag::Bag bag((dir / (std::string(name) + ".bag")).string(), rosbag::bagmode::Write);
            bag.setCompression(kind);
            for (int k = 0; k < 3; ++k) {
                bag.write("/velodyne_points", ros::Time(100.0 + 0.1 * k),
                          to_point_cloud2(sample_cloud(), 100.0 + 0.1 * k, "velodyne"));
            }
        }
        const BagCheckResult ok = check_bag_structure(dir / (std::string(name) + ".bag"));
        EXPECT_EQ(ok.compressed_chunks, 1u) << name;
        EXPECT_EQ(ok.messages, 3u) << name;
        EXPECT_EQ(check_bag_structure(dir / (std::string(name) + ".bag"), no_walk).messages, 0u)
            << name;
    }
    const std::string good = slurp(dir / "bz2.bag");
    const std::size_t header_len = u32_at(good, 13);
    const std::size_t chunk = 13 + 4 + header_len + 4 + u32_at(good, 13 + 4 + header_len);
    const std::size_t chunk_header_len = u32_at(good, chunk);
    const std::string chunk_header = good.substr(chunk + 4, chunk_header_len);
    const std::size_t data_len_at = chunk + 4 + chunk_header_len, data_at = data_len_at + 4;
    const std::size_t packed_len = u32_at(good, data_len_at);
    const std::size_t size_field = chunk + 4 + chunk_header.find("size=") + 5;
    const std::uint32_t raw_len = u32_at(good, size_field);
    const std::size_t index_pos_at =
        13 + 4 + std::string(good.data() + 17, header_len).find("index_pos=") + 10;
    const auto write = [&](const std::string& file, const std::string& bytes) {
        std::ofstream(dir / file, std::ios::binary) << bytes;
        return dir / file;
    };
    const auto put32 = [](std::string& b, std::size_t at, std::uint32_t v) {
        std::memcpy(b.data() + at, &v, 4);
    };
    const auto fails = [&](const std::filesystem::path& p, const std::string& part) {
        expect_file_error([p] { check_bag_structure(p); }, part);
    };
    const std::string at_chunk = "record at byte " + std::to_string(chunk) + " (chunk): ";
    // Damaged compressed bytes: bz2's own checks refuse them.
    std::string b = good;
    for (std::size_t i = data_at + packed_len / 2; i < data_at + packed_len / 2 + 16; ++i)
        b[i] = static_cast<char>(b[i] ^ 0x5A);
    fails(write("flipped.bag", b), at_chunk + "its bz2 data ");  // damaged, or inflating to more
    // A declared size the data does not inflate to.
    b = good;
    put32(b, size_field, raw_len - 1);
    fails(write("short.bag", b), at_chunk + "its bz2 data does not inflate to the " +
                                     std::to_string(raw_len - 1) + " bytes it declares (" +
                                     std::to_string(raw_len) + ")");
    // Records inside the chunk declaring a 4 GB header, or data past the chunk's end: the chunk
    // inflated, damaged, packed again (the bag's index moved by the new length).
    std::string raw(raw_len, '\0');
    unsigned int got = raw_len;
    std::string packed = good.substr(data_at, packed_len);
    ASSERT_EQ(BZ2_bzBuffToBuffDecompress(raw.data(), &got, packed.data(),
                                         static_cast<unsigned int>(packed_len), 0, 0),
              BZ_OK);
    const auto repacked_with = [&](std::size_t at, std::uint32_t value) {
        std::string damaged = raw;
        put32(damaged, at, value);
        std::string repacked(raw_len + raw_len / 100 + 600, '\0');
        unsigned int repacked_len = static_cast<unsigned int>(repacked.size());
        EXPECT_EQ(BZ2_bzBuffToBuffCompress(repacked.data(), &repacked_len, damaged.data(), raw_len,
                                           9, 0, 0),
                  BZ_OK);
        std::string out = good.substr(0, data_at) + repacked.substr(0, repacked_len) +
                          good.substr(data_at + packed_len);
        put32(out, data_len_at, repacked_len);
        std::uint64_t index_pos = 0;
        std::memcpy(&index_pos, out.data() + index_pos_at, 8);
        index_pos = index_pos + repacked_len - packed_len;
        std::memcpy(out.data() + index_pos_at, &index_pos, 8);
        return out;
    };
    const std::string inflated = "chunk at byte " + std::to_string(chunk) + ", inflated: ";
    fails(write("inner.bag", repacked_with(0, 0xFFFFFFF0u)),
          inflated + "record at byte 0: declares a header of 4294967280 bytes");
    EXPECT_NO_THROW(
        check_bag_structure(dir / "inner.bag", no_walk));  // what the walk alone used to see
    fails(write("inner_data.bag", repacked_with(4 + u32_at(raw, 0), 0xFFFFFFF0u)),
          inflated +
              "record at byte 0 (connection): declares 4294967280 bytes of data, past the "
              "end of its chunk");
    // An index entry pointing into a message of the compressed chunk.
    b = good;
    const std::size_t index_record = data_at + packed_len;
    const std::size_t index_header_len = u32_at(b, index_record);
    const std::size_t first_offset = index_record + 4 + index_header_len + 4 + 8;
    put32(b, first_offset, u32_at(b, first_offset) + 1);
    fails(write("index.bag", b), "entry 0 points to byte " +
                                     std::to_string(u32_at(good, first_offset) + 1) +
                                     " of its chunk, where no message starts");
}

// Messages that deserialise to nothing sane are named (topic, index, bag time); with
// skip_bad_messages the good ones are read and the bad ones counted.
TEST(Bag, LyingMessagesAreNamedOrSkipped) {
    const auto dir = fresh_dir("bag_lying");
    const sensor_msgs::PointCloud2 cloud = to_point_cloud2(sample_cloud(), 100.0, "velodyne");
    const testing::LyingMessage good = testing::as_bytes(cloud);
    std::vector<std::pair<std::string, testing::LyingMessage>> clouds;  // (what, message)
    clouds.emplace_back("good", good);
    testing::LyingMessage m = good;
    m.bytes.resize(5);
    clouds.emplace_back("5 bytes", m);
    m = good;
    m.bytes.resize(200);
    clouds.emplace_back("cut", m);
    m = good;  // data's length says 0xFFFFFFF0 (data, then is_dense, end the message)
    {
        const std::size_t data_len_at = m.bytes.size() - 1 - cloud.data.size() - 4;
        const std::uint32_t huge = 0xFFFFFFF0u;
        std::memcpy(m.bytes.data() + data_len_at, &huge, 4);
    }
    clouds.emplace_back("huge data", m);
    sensor_msgs::PointCloud2 wide = cloud;
    wide.fields[0].datatype = PointField::FLOAT64;  // x over x's and y's bytes
    clouds.emplace_back("overlap", testing::as_bytes(wide));
    sensor_msgs::PointCloud2 slow = cloud;
    put(slow, 2, 18, 1e9f);  // a per-point time of 1e9 s
    clouds.emplace_back("time", testing::as_bytes(slow));
    clouds.emplace_back("good",
                        testing::as_bytes(to_point_cloud2(sample_cloud(), 100.6, "velodyne")));
    {
        rosbag::Bag bag((dir / "clouds.bag").string(), rosbag::bagmode::Write);
        for (std::size_t k = 0; k < clouds.size(); ++k)
            bag.write("/velodyne_points", ros::Time(100.0 + 0.1 * k), clouds[k].second);
        const nav_msgs::Odometry odom =
            to_odometry(Pose2{1.0, 2.0, 0.3}, 0.0, 0.0, 100.0, "odom", "base_link");
        bag.write("/odom", ros::Time(100.0), odom);
        nav_msgs::Odometry nan_q = odom;
        nan_q.header.stamp = ros::Time(100.1);
        nan_q.pose.pose.orientation.w = NAN;
        bag.write("/odom", ros::Time(100.1), nan_q);
        nav_msgs::Odometry zero_q = odom;
        zero_q.header.stamp = ros::Time(100.2);
        zero_q.pose.pose.orientation = geometry_msgs::Quaternion();
        zero_q.pose.pose.orientation.w = 0.0;
        bag.write("/odom", ros::Time(100.2), zero_q);
        nav_msgs::Odometry far = odom;
        far.header.stamp = ros::Time(100.3);
        far.pose.pose.position.x = 1e30;
        bag.write("/odom", ros::Time(100.3), far);
        testing::LyingMessage short_odom = testing::as_bytes(odom);
        short_odom.bytes.resize(30);
        bag.write("/odom", ros::Time(100.4), short_odom);
        nav_msgs::Odometry unnormalised =
            to_odometry(Pose2{1.5, 2.0, 0.3}, 0.0, 0.0, 100.5, "odom", "base_link");
        unnormalised.pose.pose.orientation.z *= 3.0;
        unnormalised.pose.pose.orientation.w *= 3.0;
        bag.write("/odom", ros::Time(100.5), unnormalised);
    }
    // Without skipping: the first bad odometry message ends it, named.
    expect_file_error(
        [&] { BagReader r(dir / "clouds.bag", {}, true); },
        "/odom message 1 (bag time 100.100 s): the orientation quaternion is zero or not finite");
    BagReader r(dir / "clouds.bag", {}, true, true);
    EXPECT_EQ(r.skipped(), 4u);  // NaN and zero quaternions, 1e30 m, 30 bytes
    ASSERT_EQ(r.odometry().size(), 2u);
    EXPECT_NEAR(r.odometry()[1].pose.x_m, 1.5, 1e-12);
    EXPECT_NEAR(r.odometry()[1].pose.yaw_rad, 0.3, 1e-12);  // the unnormalised quaternion's yaw
    std::vector<std::size_t> read;
    while (auto s = r.next()) read.push_back(s->index);
    EXPECT_EQ(read, (std::vector<std::size_t>{0, 6}));
    EXPECT_EQ(r.skipped(), 4u + 5u);
    // Each bad cloud, after a good one, names its problem.
    const std::vector<std::string> expected = {
        "/velodyne_points message 1 (bag time 100.100 s): the header needs 12 bytes, the message "
        "has 5 left",
        "/velodyne_points message 1 (bag time 100.100 s): data needs",
        "data needs 4294967280 bytes",
        "fields 'x' and 'y' overlap (offsets 0 and 4, 8 and 4 bytes)",
        "field 'time' spans 1000000000.000000 s, more than 1.0 s"};
    for (std::size_t k = 0; k < expected.size(); ++k) {
        const auto path = dir / ("bad" + std::to_string(k) + ".bag");
        {
            rosbag::Bag bag(path.string(), rosbag::bagmode::Write);
            bag.write("/velodyne_points", ros::Time(100.0), good);
            bag.write("/velodyne_points", ros::Time(100.1), clouds[k + 1].second);
        }
        BagReader strict(path, {}, false);
        ASSERT_TRUE(strict.next()) << clouds[k + 1].first;
        expect_file_error([&] { strict.next(); }, expected[k]);
    }
    // A topic recorded under another definition of PointCloud2 (rosbag keeps one md5sum per topic:
    // the first message's): refused by name, not read with this definition's layout.
    {
        rosbag::Bag bag((dir / "md5.bag").string(), rosbag::bagmode::Write);
        testing::LyingMessage lie = good;
        lie.md5 = "0123456789abcdef0123456789abcdef";
        bag.write("/velodyne_points", ros::Time(100.0), lie);
    }
    BagReader other(dir / "md5.bag", {}, false);
    expect_file_error([&] { other.next(); },
                      "/velodyne_points message 0 (bag time 100.000 s): its md5sum "
                      "0123456789abcdef0123456789abcdef "
                      "is not sensor_msgs/PointCloud2's 1158d486dd51d683ce2f1be655c3c181");
}

}  // namespace
}  // namespace makeway::rosio
