// makeway_node against a real ROS master (Debian's rosmaster): a drive recorded by `makeway
// simulate --format bag` is played into the node at twice its rate; the node must process every
// sweep, publish the pose every sweep and the costmap, markers and object map every keyframe, with
// the stamps of the data they used, and map the room's chair and table where they stand. C++17.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "process_util.hpp"
#include "ros/msg_conversions.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using makeway::testing::read_text;
using makeway::testing::spawn;
using makeway::testing::stop;

TEST(MakewayNode, PlaysABagAtTwiceItsRateAndMapsTheRoom) {
    const fs::path dir = fs::temp_directory_path() / "makeway_test_node";
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(fs::path(MAKEWAY_SOURCE_DIR) / "tests" / "data" / "room_chair_table.yaml",
                  dir / "room.yaml");
    const std::string sim = std::string(MAKEWAY_BIN) + " simulate --scene " +
                            (dir / "room.yaml").string() + " --frames 60 --format bag --out " +
                            (dir / "sim").string() + " > " + (dir / "sim.log").string() + " 2>&1";
    ASSERT_EQ(std::system(sim.c_str()), 0) << read_text(dir / "sim.log");

    // A master of our own on a free port, logs in the test's folder.
    const int port = 20000 + static_cast<int>(getpid() % 20000);
    const std::string uri = "http://localhost:" + std::to_string(port);
    setenv("ROS_MASTER_URI", uri.c_str(), 1);
    setenv("ROS_HOSTNAME", "localhost", 1);
    setenv("ROS_HOME", dir.c_str(), 1);
    setenv("ROS_LOG_DIR", dir.c_str(), 1);
    const pid_t master =
        spawn({"rosmaster", "--core", "-p", std::to_string(port)}, dir / "master.log");
    ASSERT_GT(master, 0) << "rosmaster not found (scripts/install-deps.sh --ros)";
    int argc = 1;
    char name[] = "makeway_node_test";
    char* argv[] = {name, nullptr};
    ros::init(argc, argv, "makeway_node_test",
              ros::init_options::NoSigintHandler | ros::init_options::AnonymousName);
    for (int i = 0; i < 100 && !ros::master::check(); ++i) std::this_thread::sleep_for(100ms);
    ASSERT_TRUE(ros::master::check()) << read_text(dir / "master.log");
    const pid_t node = spawn({MAKEWAY_NODE_BIN, "__name:=makeway",
                              std::string("_model:=") + MAKEWAY_SOURCE_DIR + "/models/detector.pt"},
                             dir / "node.log");
    ASSERT_GT(node, 0);

    ros::NodeHandle nh;
    std::mutex mutex;
    std::vector<double> pose_stamps, pose_arrivals;
    std::size_t costmaps = 0, markers = 0;
    std::string last_map;
    nav_msgs::OccupancyGrid last_grid;
    const auto now = [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    };
    ros::Subscriber s1 = nh.subscribe<nav_msgs::Odometry>(
        "/makeway/odometry", 1000, [&](const nav_msgs::OdometryConstPtr& m) {
            std::lock_guard<std::mutex> lock(mutex);
            pose_stamps.push_back(m->header.stamp.toSec());
            pose_arrivals.push_back(now());
        });
    ros::Subscriber s2 = nh.subscribe<nav_msgs::OccupancyGrid>(
        "/makeway/costmap", 100, [&](const nav_msgs::OccupancyGridConstPtr& m) {
            std::lock_guard<std::mutex> lock(mutex);
            ++costmaps;
            last_grid = *m;
        });
    ros::Subscriber s3 = nh.subscribe<visualization_msgs::MarkerArray>(
        "/makeway/objects", 100, [&](const visualization_msgs::MarkerArrayConstPtr&) {
            std::lock_guard<std::mutex> lock(mutex);
            ++markers;
        });
    ros::Subscriber s4 = nh.subscribe<std_msgs::String>("/makeway/object_map", 100,
                                                        [&](const std_msgs::StringConstPtr& m) {
                                                            std::lock_guard<std::mutex> lock(mutex);
                                                            last_map = m->data;
                                                        });
    ros::Publisher clouds = nh.advertise<sensor_msgs::PointCloud2>("/velodyne_points", 100);
    ros::Publisher odom = nh.advertise<nav_msgs::Odometry>("/odom", 1000);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    // The node is up when it subscribes and publishes (it loads the detector first).
    for (int i = 0; i < 300 && (clouds.getNumSubscribers() == 0 || odom.getNumSubscribers() == 0 ||
                                s1.getNumPublishers() == 0 || s4.getNumPublishers() == 0);
         ++i) {
        std::this_thread::sleep_for(100ms);
    }
    ASSERT_GT(clouds.getNumSubscribers(), 0u) << read_text(dir / "node.log");
    ASSERT_GT(s4.getNumPublishers(), 0u) << read_text(dir / "node.log");

    // Play the bag at 2x: each message when its (halved) time comes.
    rosbag::Bag bag((dir / "sim" / "drive.bag").string());
    rosbag::View view(bag,
                      rosbag::TopicQuery(std::vector<std::string>{"/velodyne_points", "/odom"}));
    const double t0 = view.getBeginTime().toSec(), wall0 = now();
    std::vector<double> sweep_ends;
    double last_sweep_published = 0.0;
    for (const rosbag::MessageInstance& m : view) {
        const double due = wall0 + (m.getTime().toSec() - t0) / 2.0;
        if (due > now()) std::this_thread::sleep_for(std::chrono::duration<double>(due - now()));
        if (const auto c = m.instantiate<sensor_msgs::PointCloud2>()) {
            clouds.publish(c);
            sweep_ends.push_back(c->header.stamp.toSec() + 0.1);
            last_sweep_published = now();
        } else if (const auto o = m.instantiate<nav_msgs::Odometry>()) {
            odom.publish(o);
        }
    }
    const double played_s = now() - wall0;
    for (int i = 0; i < 300; ++i) {
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (pose_stamps.size() >= sweep_ends.size()) break;
        }
        std::this_thread::sleep_for(100ms);
    }
    stop(node, SIGINT);
    spinner.stop();
    ros::shutdown();
    stop(master, SIGTERM);
    const std::string log = read_text(dir / "node.log");

    std::lock_guard<std::mutex> lock(mutex);
    ASSERT_EQ(sweep_ends.size(), 60u);
    // Every sweep processed (none dropped), each output stamped with its sweep's end.
    ASSERT_EQ(pose_stamps.size(), sweep_ends.size()) << log;
    for (std::size_t i = 0; i < sweep_ends.size(); ++i)
        EXPECT_NEAR(pose_stamps[i], sweep_ends[i], 1e-3) << i;
    EXPECT_EQ(costmaps, 12u);
    EXPECT_EQ(markers, 12u);
    EXPECT_EQ(last_grid.header.frame_id, "map");
    // It kept up: the last pose came soon after the last sweep was played (6 s of data in ~3 s).
    const double lag = pose_arrivals.back() - last_sweep_published;
    std::cout << "[          ] played 60 sweeps in " << played_s << " s; last pose " << lag
              << " s after the last sweep\n";
    EXPECT_LT(lag, 1.0);
    EXPECT_NE(log.find("60 sweeps received, 60 processed, 0 dropped, 12 keyframes"),
              std::string::npos)
        << log;
    // The room's chair and table where they stand.
    const nlohmann::json map = nlohmann::json::parse(last_map);
    bool chair = false, table = false;
    for (const auto& o : map["objects"]) {
        const auto& c = o["box_world"]["centre_m"];
        const double x = c[0].get<double>(), y = c[1].get<double>();
        chair |= o["class"] == "chair" && std::hypot(x + 1.0, y - 1.0) < 0.3;
        table |= o["class"] == "table" && std::hypot(x - 1.5, y + 1.3) < 0.3;
    }
    EXPECT_TRUE(chair) << last_map;
    EXPECT_TRUE(table) << last_map;
}

}  // namespace
