// makeway_node: the online system as a ROS 1 node that maps and drives. Subscribes to a
// PointCloud2 topic, a wheel odometry topic, goals and cancels; publishes, with the stamp of the
// sweep each output used:
//   /cmd_vel (geometry_msgs/Twist): the guarded command (navigator, then collision monitor) as
//     soon as a sweep yields it, and at ~control_rate; zero when no sweep ended within
//     ~sensor_timeout or no odometry came within ~odom_timeout, when idle, on cancel, on a goal
//     it cannot reach, and before it exits;
//   ~plan (nav_msgs/Path) and ~status (std_msgs/String, JSON: state idle/driving/reached/blocked/
//     stopped, why, distance_left_m, goal), every sweep;
//   ~odometry (nav_msgs/Odometry) and /tf map -> odom (the correction of the wheel odometry, whose
//     driver publishes odom -> base_link; map -> base_link when no odometry covers the sweep),
//     every sweep;
//   ~costmap (nav_msgs/OccupancyGrid, nav2's value mapping), ~objects (visualization_msgs/
//   MarkerArray: boxes, labels, affordance zones) and ~object_map (std_msgs/String, JSON), every
//   keyframe.
// Goals: /move_base_simple/goal (geometry_msgs/PoseStamped in ~frame_id; RViz's "2D Nav Goal");
// ~cancel (std_msgs/Empty).
// Parameters (private): config, model, cad, map, zones (paths; the program's formats), cloud_topic
// (/velodyne_points), odom_topic (/odom), frame_id (map), base_frame (base_link), odom_frame
// (odom), costmap_size (40 m), queue (600 sweeps), start ("x y yaw"; default: the first odometry
// pose), extrinsics
// ("x y z roll pitch yaw": the sensor on the base; default: the configuration's robot),
// control_rate (10 Hz), sensor_timeout (0.3 s), odom_timeout (0.3 s), async_perception (true: the
// keyframe chain on its own thread, so a keyframe never delays a command; the costmap is
// published on the sweeps that form keyframes, objects and object_map when perception ends),
// perception_nice (10: that thread yields the cores to the control path), perception_threads
// (0: every core but one). The
// system runs on the engine's worker thread; the callbacks only convert and enqueue. C++17: ROS 1's
// message headers do not compile as C++20.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/error.hpp"
#include "io/pose_io.hpp"
#include "ros/msg_conversions.hpp"
#include "ros/node_engine.hpp"
#include "ros/node_util.hpp"

namespace {

using namespace makeway;

using rosio::param;

// "a b c ..." -> n finite numbers; false on anything else.
bool numbers(const std::string& text, std::size_t n, std::vector<double>& out) {
    std::istringstream in(text);
    out.clear();
    double v = 0.0;
    while (in >> v) out.push_back(v);
    if (!in.eof() || out.size() != n) return false;
    for (double x : out) {
        if (!std::isfinite(x)) return false;
    }
    return true;
}

geometry_msgs::Twist twist_of(const VelocityCommand& c) {
    geometry_msgs::Twist t;
    t.linear.x = c.v_mps;
    t.angular.z = c.w_radps;
    return t;
}

nav_msgs::Path path_of(const std::vector<Eigen::Vector2d>& plan, double stamp_s,
                       const std::string& frame) {
    nav_msgs::Path path;
    path.header.stamp = rosio::to_ros_time(stamp_s);
    path.header.frame_id = frame;
    for (const Eigen::Vector2d& p : plan) {
        geometry_msgs::PoseStamped q;
        q.header = path.header;
        q.pose.position.x = p.x();
        q.pose.position.y = p.y();
        q.pose.orientation.w = 1.0;
        path.poses.push_back(q);
    }
    return path;
}

}  // namespace

int main(int argc, char** argv) {
    ros::init(argc, argv, "makeway", ros::init_options::NoSigintHandler);
    rosio::install_stop_signals();
    ros::NodeHandle nh, pnh("~");
    rosio::NodeSettings settings;
    settings.config = param<std::string>(pnh, "config", "");
    settings.model = param<std::string>(pnh, "model", "");
    settings.cad = param<std::string>(pnh, "cad", "");
    settings.map = param<std::string>(pnh, "map", "");
    settings.zones = param<std::string>(pnh, "zones", "");
    settings.costmap_size_m = param<double>(pnh, "costmap_size", 40.0);
    settings.max_queue = static_cast<std::size_t>(std::max(1, param<int>(pnh, "queue", 600)));
    settings.sensor_timeout_s = param<double>(pnh, "sensor_timeout", 0.3);
    settings.odometry_timeout_s = param<double>(pnh, "odom_timeout", 0.3);
    settings.async_perception = param<bool>(pnh, "async_perception", true);
    settings.perception_nice = param<int>(pnh, "perception_nice", 10);
    settings.perception_threads = param<int>(pnh, "perception_threads", 0);
    const double control_rate = param<double>(pnh, "control_rate", 10.0);
    const std::string cloud_topic = param<std::string>(pnh, "cloud_topic", "/velodyne_points");
    const std::string odom_topic = param<std::string>(pnh, "odom_topic", "/odom");
    const std::string frame = param<std::string>(pnh, "frame_id", "map");
    const std::string base = param<std::string>(pnh, "base_frame", "base_link");
    const std::string odom_frame = param<std::string>(pnh, "odom_frame", "odom");
    std::vector<double> v;
    const std::string start = param<std::string>(pnh, "start", "");
    if (!start.empty()) {
        if (!numbers(start, 3, v)) {
            ROS_FATAL("makeway_node: ~start: expected \"x y yaw\" (3 finite numbers), got \"%s\"",
                      start.c_str());
            return 2;
        }
        if (const std::string p = io::start_problem(v); !p.empty()) {
            ROS_FATAL("makeway_node: ~start: %s", p.c_str());
            return 2;
        }
        settings.start = Pose2{v[0], v[1], v[2]};
    }
    const std::string extrinsics = param<std::string>(pnh, "extrinsics", "");
    if (!extrinsics.empty()) {
        if (!numbers(extrinsics, 6, v)) {
            ROS_FATAL(
                "makeway_node: ~extrinsics: expected \"x y z roll pitch yaw\" (6 finite numbers), "
                "got \"%s\"",
                extrinsics.c_str());
            return 2;
        }
        if (const std::string p = io::extrinsics_problem(v); !p.empty()) {
            ROS_FATAL("makeway_node: ~extrinsics: %s", p.c_str());
            return 2;
        }
        settings.T_base_sensor = make_T_xyz_rpy({v[0], v[1], v[2]}, v[3], v[4], v[5]);
    }
    if (!(control_rate > 0.0 && control_rate <= 1000.0) || !(settings.sensor_timeout_s > 0.0) ||
        !(settings.odometry_timeout_s > 0.0)) {
        ROS_FATAL(
            "makeway_node: ~control_rate must be in (0, 1000] Hz, ~sensor_timeout and "
            "~odom_timeout > 0 s");
        return 2;
    }

    ros::Publisher odometry_pub = pnh.advertise<nav_msgs::Odometry>("odometry", 50);
    ros::Publisher tf_pub = nh.advertise<tf2_msgs::TFMessage>("/tf", 50);
    ros::Publisher costmap_pub = pnh.advertise<nav_msgs::OccupancyGrid>("costmap", 5, true);
    ros::Publisher objects_pub = pnh.advertise<visualization_msgs::MarkerArray>("objects", 5, true);
    ros::Publisher map_pub = pnh.advertise<std_msgs::String>("object_map", 5, true);
    ros::Publisher cmd_pub = nh.advertise<geometry_msgs::Twist>("/cmd_vel", 10);
    ros::Publisher plan_pub = pnh.advertise<nav_msgs::Path>("plan", 5, true);
    ros::Publisher status_pub = pnh.advertise<std_msgs::String>("status", 20, true);

    // Sweep arrival to /cmd_vel [ms], and the control timer's lateness.
    std::mutex stats_mutex;
    std::vector<double> latencies, waits, works, keyframe_works, front_ends, navigations;
    std::size_t cycles = 0, late_cycles = 0;
    settings.clock = [] { return ros::Time::now().toSec(); };
    settings.send_command = [&cmd_pub](const VelocityCommand& c) { cmd_pub.publish(twist_of(c)); };
    // The callback runs on the engine's worker, also while the engine is destroyed (it finishes
    // what is queued): it must not call the engine.
    costmap::AffordanceParams zones;
    std::unique_ptr<rosio::NodeEngine> engine;
    try {
        engine = std::make_unique<rosio::NodeEngine>(settings, [&](const rosio::NodeOutput& out) {
            // The command went first (settings.send_command, under the engine's lock).
            if (!out.notice.empty()) ROS_WARN("makeway_node: %s", out.notice.c_str());
            if (!out.object_map_json
                     .empty()) {  // a finished keyframe (in line, or from the perception thread)
                objects_pub.publish(rosio::to_markers(out.objects, zones, out.stamp_s, frame));
                std_msgs::String text;
                text.data = out.object_map_json;
                map_pub.publish(text);
            }
            if (out.perception) {
                std::lock_guard<std::mutex> lock(stats_mutex);
                keyframe_works.push_back(out.keyframe_ms);  // off the control path
                return;
            }
            {
                std::lock_guard<std::mutex> lock(stats_mutex);
                latencies.push_back(out.latency_ms);
                waits.push_back(out.queue_wait_ms);
                (out.keyframe && !settings.async_perception ? keyframe_works : works)
                    .push_back(out.latency_ms - out.queue_wait_ms);
                front_ends.push_back(out.front_end_ms);
                navigations.push_back(out.navigation_ms);
            }
            odometry_pub.publish(rosio::to_odometry(out.pose, 0.0, 0.0, out.stamp_s, frame, base));
            // ROS's frame chain: the odometry owns odom -> base_link, so the map's correction is
            // map -> odom (the estimate times the inverse of the wheels); map -> base_link only
            // without wheel odometry.
            if (out.wheel_pose) {
                const Pose2 map_odom =
                    to_pose2(to_isometry(out.pose) * to_isometry(*out.wheel_pose).inverse());
                tf_pub.publish(rosio::to_tf(lift_to_3d(map_odom), out.stamp_s, frame, odom_frame));
            } else {
                tf_pub.publish(rosio::to_tf(lift_to_3d(out.pose), out.stamp_s, frame, base));
            }
            plan_pub.publish(path_of(out.plan, out.stamp_s, frame));
            std_msgs::String status;
            status.data = rosio::to_json(out.status);
            status_pub.publish(status);
            if (out.keyframe)
                costmap_pub.publish(rosio::to_occupancy_grid(*out.costmap, out.stamp_s, frame));
        });
    } catch (const std::exception& e) {
        ROS_FATAL("makeway_node: %s", e.what());
        return 2;
    }
    zones = engine->zones();  // before any sweep can arrive (the subscribers come next)
    // Callbacks convert and enqueue only (a slow keyframe never blocks them).
    ros::Subscriber clouds = nh.subscribe<sensor_msgs::PointCloud2>(
        cloud_topic, 100,
        [&](const sensor_msgs::PointCloud2ConstPtr& msg) {
            try {
                engine->push_sweep(rosio::from_point_cloud2(*msg));
            } catch (const io::FormatError& e) {
                ROS_ERROR_THROTTLE(5.0, "makeway_node: %s: %s (sweep skipped)", cloud_topic.c_str(),
                                   e.what());
            }
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
    // TCP_NODELAY: small messages (odometry at 50-100 Hz) otherwise wait for Nagle's algorithm and
    // the peer's delayed ACK, ~40 ms: a sweep then waits that long for the odometry of its end.
    ros::Subscriber odometry = nh.subscribe<nav_msgs::Odometry>(
        odom_topic, 1000,
        [&](const nav_msgs::OdometryConstPtr& msg) {
            try {
                engine->push_odometry({msg->header.stamp.toSec(), rosio::pose_from_odometry(*msg)});
            } catch (const io::FormatError& e) {
                ROS_ERROR_THROTTLE(5.0, "makeway_node: %s: %s (message skipped)",
                                   odom_topic.c_str(), e.what());
            }
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
    ros::Subscriber goals = nh.subscribe<geometry_msgs::PoseStamped>(
        "/move_base_simple/goal", 5, [&](const geometry_msgs::PoseStampedConstPtr& msg) {
            if (!msg->header.frame_id.empty() && msg->header.frame_id != frame) {
                ROS_WARN("makeway_node: goal in frame \"%s\" ignored: goals are in \"%s\"",
                         msg->header.frame_id.c_str(), frame.c_str());
                return;
            }
            const Eigen::Vector2d goal(msg->pose.position.x, msg->pose.position.y);
            if (!goal.allFinite())
                ROS_WARN("makeway_node: goal is not finite: the robot stays still");
            engine->set_goal(goal);
        });
    ros::Subscriber cancels =
        pnh.subscribe<std_msgs::Empty>("cancel", 5, [&](const std_msgs::EmptyConstPtr&) {
            engine->cancel();  // sends zero at once, not at the next cycle
        });
    // The control rate: the last command while the data are fresh, zero otherwise.
    std::string last_why;
    ros::Timer control =
        nh.createTimer(ros::Duration(1.0 / control_rate), [&](const ros::TimerEvent& e) {
            {
                std::lock_guard<std::mutex> lock(stats_mutex);
                ++cycles;
                late_cycles += !e.last_real.isZero() &&
                               (e.current_real - e.last_real).toSec() > 1.5 / control_rate;
            }
            const rosio::GatedCommand gated = engine->send_command_at(ros::Time::now().toSec());
            if (!gated.why.empty() && gated.why != last_why)
                ROS_WARN_THROTTLE(5.0, "makeway_node: zero velocity: %s", gated.why.c_str());
            last_why = gated.why;
        });
    ROS_INFO(
        "makeway_node: %s + %s + /move_base_simple/goal -> /cmd_vel, "
        "%s/{plan,status,odometry,costmap,objects,object_map}",
        cloud_topic.c_str(), odom_topic.c_str(), pnh.getNamespace().c_str());
    ros::AsyncSpinner spinner(3);  // clouds, odometry and the control timer on their own threads
    spinner.start();
    while (!rosio::stop_requested() && ros::ok())
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    // Safe on the way out: the motors get zero before anything stops.
    engine->cancel();
    for (int i = 0; i < 3; ++i) {
        cmd_pub.publish(twist_of({}));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    control.stop();
    spinner.stop();
    engine->drain();  // what is queued, perceived and published while ROS is up
    std::this_thread::sleep_for(
        std::chrono::milliseconds(200));  // roscpp sends from its own threads
    const rosio::NodeStats s = engine->stats();
    engine.reset();
    ros::shutdown();
    std::printf(
        "makeway_node: %zu sweeps received, %zu processed, %zu dropped, %zu keyframes, queue at "
        "most %zu\n",
        s.received, s.processed, s.dropped, s.keyframes, s.max_queue);
    if (!latencies.empty()) {
        const auto at = [](std::vector<double> sample, double q) {
            if (sample.empty()) return 0.0;
            std::sort(sample.begin(), sample.end());
            return sample[static_cast<std::size_t>(q * static_cast<double>(sample.size() - 1))];
        };
        std::printf(
            "makeway_node: sweep to /cmd_vel: median %.1f ms, p99 %.1f ms, max %.1f ms (queued "
            "%.1f ms median, p99 %.1f; "
            "processing %.1f ms median, p99 %.1f: front end %.1f / %.1f, navigation %.1f / %.1f; "
            "keyframe chain %.1f ms median, %s); "
            "control cycles %zu, late (> 1.5 periods) %zu\n",
            at(latencies, 0.5), at(latencies, 0.99), at(latencies, 1.0), at(waits, 0.5),
            at(waits, 0.99), at(works, 0.5), at(works, 0.99), at(front_ends, 0.5),
            at(front_ends, 0.99), at(navigations, 0.5), at(navigations, 0.99),
            at(keyframe_works, 0.5), settings.async_perception ? "on its own thread" : "in line",
            cycles, late_cycles);
    }
    std::fflush(stdout);
    return 0;
}
