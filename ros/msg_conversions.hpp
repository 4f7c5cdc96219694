#pragma once
// Conversions between makeway's types and ROS 1 messages (sensor_msgs, nav_msgs,
// visualization_msgs, tf2_msgs, std_msgs). This header includes the message headers: only the
// bag reader/writer, the ROS node and their tests include it.
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/costmap/affordance.hpp"
#include "ros/bag_io.hpp"

namespace makeway::rosio {

/// A stamp as ros::Time: seconds since the epoch, at least 1 ns (rosbag refuses time 0).
ros::Time to_ros_time(double stamp_s);

/// Reads x, y, z (float32/64), intensity (float32/64, uint8/16) and ring (uint8/16) when present,
/// and the per-point time in the layouts drivers write: `time` in seconds relative to the stamp
/// (Velodyne; float64 values above 1e6 are taken as absolute seconds), `t` in nanoseconds relative
/// to the stamp (Ouster, uint32) or seconds (float), `timestamp` in absolute seconds (Hesai,
/// float64). The sweep starts at the stamp when relative times are all >= 0, else at the first
/// point. Points with a non-finite coordinate are kept (the caller's policy decides).
/// Throws io::FormatError on a malformed message (big-endian data, data shorter than
/// width x height x point_step, fields outside the point, x/y/z missing, of an unknown type or
/// overlapping, no points, per-point times spanning more than kMaxSweepSpan_s).
CloudSweep from_point_cloud2(const sensor_msgs::PointCloud2& msg);

/// The Velodyne driver's layout: x y z intensity (float32), ring (uint16), time (float32, seconds
/// since stamp_s), unorganised (height 1).
sensor_msgs::PointCloud2 to_point_cloud2(const PointCloud& cloud, double stamp_s,
                                         const std::string& frame_id);

/// The base's planar pose from an Odometry message (yaw from the quaternion, which need not be
/// normalised). Throws io::FormatError for a non-finite position or one beyond
/// io::kMaxPosition_m, and for a zero or non-finite quaternion.
Pose2 pose_from_odometry(const nav_msgs::Odometry& msg);
nav_msgs::Odometry to_odometry(const Pose2& pose, double v_mps, double w_radps, double stamp_s,
                               const std::string& frame_id, const std::string& child_frame_id);

/// nav2's / move_base's costmap publication mapping: 0 free -> 0, 1-252 -> 1-98, 253 inscribed
/// -> 99, 254 lethal -> 100, 255 unknown -> -1.
std::int8_t occupancy_of_cost(std::uint8_t cost);
nav_msgs::OccupancyGrid to_occupancy_grid(const Costmap& costmap, double stamp_s,
                                          const std::string& frame_id);

/// Object boxes (CUBE, coloured by class, alpha by existence), their labels (TEXT: class, id,
/// existence) and their affordance zones (LINE_STRIP of costmap::zone_outline), after one
/// DELETEALL so that removed objects disappear.
visualization_msgs::MarkerArray to_markers(const std::vector<ObjectEstimate>& objects,
                                           const costmap::AffordanceParams& zones, double stamp_s,
                                           const std::string& frame_id);

tf2_msgs::TFMessage to_tf(const Isometry3& T_parent_child, double stamp_s,
                          const std::string& parent, const std::string& child);

}  // namespace makeway::rosio
