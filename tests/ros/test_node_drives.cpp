// makeway_node drives a robot over a real ROS master (Debian's rosmaster): makeway_sim_node is
// the robot (sweeps, wheel odometry, /clock; /cmd_vel in), makeway_node gets a goal on
// /move_base_simple/goal and must reach it without touching anything; a bad goal leaves the robot
// still with a status that says why; a cancel stops it within one control cycle; when the clouds
// stop mid-drive the velocity goes to zero within the sensor timeout. The truth comes from the sim
// node's report and /ground_truth/odom, never from the robot's software. C++17.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "process_util.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using makeway::testing::read_text;
using makeway::testing::spawn;
using makeway::testing::stop;

const fs::path& dir() {
    static const fs::path d = [] {
        // One folder per process: ctest runs each test in its own process, side by side.
        const fs::path p =
            fs::temp_directory_path() / ("makeway_test_node_drives_" + std::to_string(getpid()));
        fs::remove_all(p);
        fs::create_directories(p);
        return p;
    }();
    return d;
}

// One master for the whole program (roscpp initialises once per process), on sim time.
class Master : public ::testing::Environment {
  public:
    void SetUp() override {
        const int port = 20000 + static_cast<int>((getpid() + 7919) % 20000);
        const std::string uri = "http://localhost:" + std::to_string(port);
        setenv("ROS_MASTER_URI", uri.c_str(), 1);
        setenv("ROS_HOSTNAME", "localhost", 1);
        setenv("ROS_HOME", dir().c_str(), 1);
        setenv("ROS_LOG_DIR", dir().c_str(), 1);
        pid_ = spawn({"rosmaster", "--core", "-p", std::to_string(port)}, dir() / "master.log");
        ASSERT_GT(pid_, 0) << "rosmaster not found (scripts/install-deps.sh --ros)";
        int argc = 1;
        char name[] = "makeway_drive_test";
        char* argv[] = {name, nullptr};
        ros::init(argc, argv, "makeway_drive_test",
                  ros::init_options::NoSigintHandler | ros::init_options::AnonymousName);
        for (int i = 0; i < 100 && !ros::master::check(); ++i) std::this_thread::sleep_for(100ms);
        ASSERT_TRUE(ros::master::check()) << read_text(dir() / "master.log");
        ros::param::set("/use_sim_time", true);
        spinner_ = std::make_unique<ros::AsyncSpinner>(2);
        spinner_->start();
    }
    void TearDown() override {
        spinner_->stop();
        ros::shutdown();
        stop(pid_, SIGTERM);
    }

  private:
    pid_t pid_ = -1;
    std::unique_ptr<ros::AsyncSpinner> spinner_;
};

// The robot (sim node) and the system (makeway_node) on one scene, and what the test sees of them.
struct Drive {
    std::string name;
    pid_t sim = -1, node = -1;
    ros::NodeHandle nh;
    ros::Publisher goal_pub, cancel_pub;
    ros::Subscriber status_sub, cmd_sub, truth_sub;
    std::mutex mutex;
    nlohmann::json status;
    std::vector<std::pair<double, std::string>> states;  // (sim time, state)
    std::vector<std::pair<double, double>> commands;     // (sim time, |v| + |w|)
    nav_msgs::Odometry truth;
    bool have_truth = false;

    Drive(const std::string& n, const std::vector<std::string>& sim_params) : name(n) {
        std::vector<std::string> args{
            MAKEWAY_SIM_NODE_BIN, "__name:=makeway_sim",
            std::string("_scene:=") + MAKEWAY_SOURCE_DIR + "/tests/data/room_chair_table.yaml",
            "_report:=" + (dir() / (name + "_report.json")).string()};
        args.insert(args.end(), sim_params.begin(), sim_params.end());
        sim = spawn(args, dir() / (name + "_sim.log"));
        node = spawn({MAKEWAY_NODE_BIN, "__name:=makeway",
                      std::string("_model:=") + MAKEWAY_SOURCE_DIR + "/models/detector.pt"},
                     dir() / (name + "_node.log"));
        goal_pub = nh.advertise<geometry_msgs::PoseStamped>("/move_base_simple/goal", 5);
        cancel_pub = nh.advertise<std_msgs::Empty>("/makeway/cancel", 5);
        status_sub = nh.subscribe<std_msgs::String>(
            "/makeway/status", 100, [this](const std_msgs::StringConstPtr& m) {
                std::lock_guard<std::mutex> lock(mutex);
                status = nlohmann::json::parse(m->data);
                states.emplace_back(ros::Time::now().toSec(), status["state"].get<std::string>());
            });
        cmd_sub = nh.subscribe<geometry_msgs::Twist>(
            "/cmd_vel", 100, [this](const geometry_msgs::TwistConstPtr& m) {
                std::lock_guard<std::mutex> lock(mutex);
                commands.emplace_back(ros::Time::now().toSec(),
                                      std::abs(m->linear.x) + std::abs(m->angular.z));
            });
        truth_sub = nh.subscribe<nav_msgs::Odometry>("/ground_truth/odom", 100,
                                                     [this](const nav_msgs::OdometryConstPtr& m) {
                                                         std::lock_guard<std::mutex> lock(mutex);
                                                         truth = *m;
                                                         have_truth = true;
                                                     });
    }
    ~Drive() {
        // The callbacks first: the spinner's threads may still run one (a message queued before
        // the nodes stopped) while the members it writes are destroyed. One run under load
        // crashed (SEGFAULT, not reproduced alone); this race is the one found. shutdown() waits
        // for a callback in flight.
        status_sub.shutdown();
        cmd_sub.shutdown();
        truth_sub.shutdown();
        finish();
    }

    // Waits (wall time) until `done` holds; false on timeout.
    bool wait_for(const std::function<bool()>& done, double timeout_s) {
        const auto end =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < end) {
            {
                std::lock_guard<std::mutex> lock(mutex);
                if (done()) return true;
            }
            std::this_thread::sleep_for(50ms);
        }
        return false;
    }
    bool up() {  // the node listens for goals and the robot is moving its clock
        return wait_for(
            [&] {
                return goal_pub.getNumSubscribers() > 0 && cancel_pub.getNumSubscribers() > 0 &&
                       have_truth && !status.is_null();
            },
            60.0);
    }
    void send_goal(double x, double y) {
        geometry_msgs::PoseStamped g;
        g.header.frame_id = "map";
        g.header.stamp = ros::Time::now();
        g.pose.position.x = x;
        g.pose.position.y = y;
        g.pose.orientation.w = 1.0;
        goal_pub.publish(g);
    }
    std::pair<double, double> truth_xy() {
        std::lock_guard<std::mutex> lock(mutex);
        return {truth.pose.pose.position.x, truth.pose.pose.position.y};
    }
    // Stops both; the sim node's report.
    int node_exit = -1, sim_exit = -1;
    nlohmann::json finish() {
        if (node > 0) node_exit = stop(node, SIGINT), node = -1;
        if (sim > 0) sim_exit = stop(sim, SIGINT), sim = -1;
        const std::string text = read_text(dir() / (name + "_report.json"));
        return text.empty() ? nlohmann::json() : nlohmann::json::parse(text);
    }
    std::string logs() {
        return read_text(dir() / (name + "_node.log")) + "\n" +
               read_text(dir() / (name + "_sim.log"));
    }
};

TEST(MakewayNodeDrives, ReachesAGoalInARoomWithAChairAndATableWithoutTouchingAnything) {
    Drive d("reach", {});
    ASSERT_TRUE(d.up()) << d.logs();
    d.send_goal(3.5, 0.0);  // past the chair and the table, 7.5 m ahead
    const bool reached = d.wait_for([&] { return d.status["state"] == "reached"; }, 90.0);
    const nlohmann::json report = d.finish();
    EXPECT_EQ(d.node_exit, 0) << d.logs();
    EXPECT_EQ(d.sim_exit, 0) << d.logs();
    ASSERT_TRUE(reached) << d.status.dump() << "\n" << d.logs();
    ASSERT_FALSE(report.is_null()) << d.logs();
    std::cout << "[          ] reached in " << report["time_s"] << " s of sim time, "
              << report["distance_m"] << " m driven\n";
    EXPECT_LT(report["distance_to_goal_m"].get<double>(), 0.5) << report.dump();
    EXPECT_EQ(report["robot_caused_contacts"].get<int>(), 0) << report["contact_events"].dump();
    EXPECT_TRUE(report["contact_events"].empty()) << report["contact_events"].dump();
    const std::string log = d.logs();
    EXPECT_NE(log.find("sweep to /cmd_vel"), std::string::npos) << log;
}

TEST(MakewayNodeDrives, BadGoalsLeaveTheRobotStillCancelStopsAndLostCloudsStopIt) {
    // The sensor fails at 14 s of sim time.
    Drive d("safety", {"_cloud_until:=14.0"});
    ASSERT_TRUE(d.up()) << d.logs();
    const double x0 = d.truth_xy().first, y0 = d.truth_xy().second;
    // Bad goals: not finite, outside the map, inside a wall: the status says why, nothing moves.
    const std::pair<double, std::string> bad[] = {
        {std::numeric_limits<double>::quiet_NaN(), "not finite"},
        {40.0, "outside the map"},
        {0.0, "inside an obstacle"}};
    for (const auto& [x, why] : bad) {
        d.send_goal(
            x, why == "inside an obstacle" ? 2.5 : 0.0);  // (0, 2.5): in the wall the sweeps show
        ASSERT_TRUE(d.wait_for(
            [&] { return d.status["why"].get<std::string>().find(why) != std::string::npos; },
            10.0))
            << why << ": " << d.status.dump() << "\n"
            << d.logs();
        EXPECT_EQ(d.status["state"], "stopped");
    }
    std::this_thread::sleep_for(1s);
    {
        const auto [x, y] = d.truth_xy();
        EXPECT_LT(std::hypot(x - x0, y - y0), 0.01) << "the robot moved on a bad goal";
    }
    // A good goal, then a cancel once it drives: zero within one control cycle (0.1 s), and
    // nothing but zero after it (commands in flight when it was sent may still arrive first).
    d.send_goal(3.5, 0.0);
    ASSERT_TRUE(
        d.wait_for([&] { return !d.commands.empty() && d.commands.back().second > 0.3; }, 20.0))
        << d.logs();
    std::size_t sent_at = 0;
    double cancel_t = 0.0;
    {
        std::lock_guard<std::mutex> lock(d.mutex);
        sent_at = d.commands.size();
        cancel_t = ros::Time::now().toSec();
        d.cancel_pub.publish(std_msgs::Empty());
    }
    ASSERT_TRUE(d.wait_for([&] { return d.status["why"] == "cancelled"; }, 5.0)) << d.status.dump();
    {
        std::lock_guard<std::mutex> lock(d.mutex);
        std::string trace;
        std::size_t first_zero = d.commands.size();
        bool moved_after = false;
        for (std::size_t i = sent_at; i < d.commands.size(); ++i) {
            trace += std::to_string(d.commands[i].first) + ":" +
                     std::to_string(d.commands[i].second) + " ";
            if (d.commands[i].second == 0.0 && first_zero == d.commands.size()) first_zero = i;
            moved_after |= first_zero < i && d.commands[i].second != 0.0;
        }
        ASSERT_LT(first_zero, d.commands.size()) << trace;
        EXPECT_LE(d.commands[first_zero].first - cancel_t, 0.1 + 1e-6)
            << "cancel at " << cancel_t << ": " << trace;
        EXPECT_FALSE(moved_after) << "cancel at " << cancel_t << ": " << trace;
    }
    // Drive again until the clouds stop at 14 s: zero velocity within the sensor timeout (0.3 s)
    // and no motion command after it.
    d.send_goal(3.5, 0.0);
    ASSERT_TRUE(
        d.wait_for([&] { return !d.commands.empty() && d.commands.back().first > 16.0; }, 40.0))
        << d.logs();
    {
        std::lock_guard<std::mutex> lock(d.mutex);
        double last_moving = -1.0;
        bool moving_before = false;
        for (const auto& [t, speed] : d.commands) {
            if (speed > 0.0) last_moving = t;
            moving_before |= speed > 0.0 && t > 12.0 && t < 15.0;
        }
        EXPECT_TRUE(moving_before) << "the robot was not driving when the sensor failed";
        EXPECT_LE(last_moving, 1.0 + 14.0 + 0.5)
            << "a motion command came " << last_moving - 15.0 << " s after the last cloud";
    }
    const nlohmann::json report = d.finish();
    ASSERT_FALSE(report.is_null()) << d.logs();
    EXPECT_EQ(report["robot_caused_contacts"].get<int>(), 0) << report["contact_events"].dump();
}

}  // namespace

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    ::testing::AddGlobalTestEnvironment(new Master);
    return RUN_ALL_TESTS();
}
