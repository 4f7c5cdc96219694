// PointCloud2 layouts of real drivers (Velodyne, Ouster, Hesai) and malformed ones, the costmap's
// OccupancyGrid mapping, markers, and bags written then read back (damaged bags:
// test_bag_check.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/error.hpp"
#include "ros/bag_io.hpp"
#include "ros/msg_conversions.hpp"
#include "ros_test_util.hpp"

namespace makeway::rosio {
namespace {

using namespace test;

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

}  // namespace
}  // namespace makeway::rosio
