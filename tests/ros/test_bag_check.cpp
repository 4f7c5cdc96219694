// Damaged and lying bags: the structure walk that refuses what would abort rosbag (plain and
// compressed chunks), and messages that deserialise to nothing sane, named or skipped.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>

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
#include "ros_test_util.hpp"

namespace makeway::rosio {
namespace {

using namespace test;

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
