// makeway_node: the online system as a ROS 1 node. Subscribes to a PointCloud2 topic and a wheel
// odometry topic; publishes, with the stamp of the sweep each output used:
//   ~odometry (nav_msgs/Odometry) and /tf map -> base_link, every sweep;
//   ~costmap (nav_msgs/OccupancyGrid, nav2's value mapping), ~objects (visualization_msgs/
//   MarkerArray: boxes, labels, affordance zones) and ~object_map (std_msgs/String, JSON), every
//   keyframe.
// Parameters (private): config, model, cad, map (paths; the program's formats), cloud_topic
// (/velodyne_points), odom_topic (/odom), frame_id (map), base_frame (base_link), costmap_size
// (40 m), queue (600 sweeps). Perception runs on the engine's worker thread; the callbacks only
// convert and enqueue. C++17: ROS 1's message headers do not compile as C++20.
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdio>
#include <string>

#include "io/error.hpp"
#include "ros/msg_conversions.hpp"
#include "ros/node_engine.hpp"

namespace {

using namespace makeway;

template <typename T>
T param(ros::NodeHandle& nh, const std::string& name, const T& fallback) {
    T value;
    return nh.param<T>(name, value, fallback) ? value : fallback;
}

}  // namespace

int main(int argc, char** argv) {
    ros::init(argc, argv, "makeway");
    ros::NodeHandle nh, pnh("~");
    rosio::NodeSettings settings;
    settings.config = param<std::string>(pnh, "config", "");
    settings.model = param<std::string>(pnh, "model", "");
    settings.cad = param<std::string>(pnh, "cad", "");
    settings.map = param<std::string>(pnh, "map", "");
    settings.costmap_size_m = param<double>(pnh, "costmap_size", 40.0);
    settings.max_queue = static_cast<std::size_t>(std::max(1, param<int>(pnh, "queue", 600)));
    const std::string cloud_topic = param<std::string>(pnh, "cloud_topic", "/velodyne_points");
    const std::string odom_topic = param<std::string>(pnh, "odom_topic", "/odom");
    const std::string frame = param<std::string>(pnh, "frame_id", "map");
    const std::string base = param<std::string>(pnh, "base_frame", "base_link");

    ros::Publisher odometry_pub = pnh.advertise<nav_msgs::Odometry>("odometry", 50);
    ros::Publisher tf_pub = nh.advertise<tf2_msgs::TFMessage>("/tf", 50);
    ros::Publisher costmap_pub = pnh.advertise<nav_msgs::OccupancyGrid>("costmap", 5, true);
    ros::Publisher objects_pub = pnh.advertise<visualization_msgs::MarkerArray>("objects", 5, true);
    ros::Publisher map_pub = pnh.advertise<std_msgs::String>("object_map", 5, true);

    std::unique_ptr<rosio::NodeEngine> engine;
    try {
        engine = std::make_unique<rosio::NodeEngine>(settings, [&](const rosio::NodeOutput& out) {
            odometry_pub.publish(rosio::to_odometry(out.pose, 0.0, 0.0, out.stamp_s, frame, base));
            tf_pub.publish(rosio::to_tf(lift_to_3d(out.pose), out.stamp_s, frame, base));
            if (!out.keyframe) return;
            costmap_pub.publish(rosio::to_occupancy_grid(*out.costmap, out.stamp_s, frame));
            objects_pub.publish(rosio::to_markers(out.objects, engine->zones(), out.stamp_s, frame));
            std_msgs::String text;
            text.data = out.object_map_json;
            map_pub.publish(text);
        });
    } catch (const std::exception& e) {
        ROS_FATAL("makeway_node: %s", e.what());
        return 2;
    }
    // Callbacks convert and enqueue only (a slow keyframe never blocks them).
    ros::Subscriber clouds = nh.subscribe<sensor_msgs::PointCloud2>(
        cloud_topic, 100, [&](const sensor_msgs::PointCloud2ConstPtr& msg) {
            try {
                engine->push_sweep(rosio::from_point_cloud2(*msg));
            } catch (const io::FormatError& e) {
                ROS_ERROR_THROTTLE(5.0, "makeway_node: %s: %s (sweep skipped)", cloud_topic.c_str(), e.what());
            }
        });
    ros::Subscriber odometry = nh.subscribe<nav_msgs::Odometry>(odom_topic, 1000, [&](const nav_msgs::OdometryConstPtr& msg) {
        engine->push_odometry({msg->header.stamp.toSec(), rosio::pose_from_odometry(*msg)});
    });
    ROS_INFO("makeway_node: %s + %s -> %s/{odometry,costmap,objects,object_map}", cloud_topic.c_str(), odom_topic.c_str(),
             pnh.getNamespace().c_str());
    ros::AsyncSpinner spinner(2);  // clouds and odometry on their own threads
    spinner.start();
    ros::waitForShutdown();
    const rosio::NodeStats s = engine->stats();
    engine.reset();  // finishes what is queued
    // rosconsole is shut down by now: plain stdout.
    std::printf("makeway_node: %zu sweeps received, %zu processed, %zu dropped, %zu keyframes, queue at most %zu\n", s.received,
                s.processed, s.dropped, s.keyframes, s.max_queue);
    std::fflush(stdout);
    return 0;
}
