#pragma once
// ROS 1 bags in and out (Debian's rosbag_storage; no ROS master, no catkin). This header names no
// ROS type: the program's commands include it; the messages stay in bag_io.cpp and
// msg_conversions.cpp.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/costmap/affordance.hpp"

namespace makeway::rosio {

/// Per-point times spanning more than this are refused: a sweep lasts 0.05-0.2 s; 1 s is ten
/// sweep periods of the slowest common rate (a time field in the wrong unit spans 1e3-1e9 s).
constexpr double kMaxSweepSpan_s = 1.0;
/// Empty when per-point times spanning `span_s` fit one sweep, else what is wrong after the
/// subject ("spans " + this): the span, the bound and why.
std::string sweep_span_problem(double span_s);

/// A stamp as errors show it: seconds with 3 decimals.
std::string seconds_text(double t_s);

/// A sweep read from a PointCloud2: points in the message's frame, time since the first point.
struct CloudSweep {
    PointCloud points;
    double stamp_s =
        0.0;  ///< the sweep's start: the header stamp, or the first point when times run before it
    double duration_s = 0.0;  ///< last point's time - stamp_s (0 without a time field)
    bool timed = false;       ///< a per-point time field was found
    std::string time_field;  ///< its name: time (Velodyne), t (Ouster), timestamp (Hesai), or empty
    std::string frame_id;
    std::size_t index = 0;  ///< the message's index on its topic (bags; skipped messages count)
};

struct StampedPose2 {
    double stamp_s = 0.0;
    Pose2 pose;
};

struct BagTopics {
    std::string cloud = "/velodyne_points";  ///< sensor_msgs/PointCloud2
    std::string odometry = "/odom";          ///< nav_msgs/Odometry (wheel odometry of the base)
};

/// A bag's sweeps, one at a time in time order (bags are large), and its odometry, read whole.
class BagReader {
  public:
    /// Throws io::FileError naming the bag: not a readable bag; no PointCloud2 messages on the
    /// cloud topic (the message lists the PointCloud2 topics it has); a topic of another type; with
    /// `require_odometry`, the same for the odometry topic.
    /// The bag's structure is checked first (check_bag_structure). A message that does not
    /// deserialise or holds nonsense (from_point_cloud2, pose_from_odometry) is an io::FileError
    /// "BAG: TOPIC message K (bag time T s): problem", or with `skip_bad_messages` skipped and
    /// counted (skipped()); odometry is read whole here, so its bad messages are counted at once.
    BagReader(const std::filesystem::path& path, const BagTopics& topics, bool require_odometry,
              bool skip_bad_messages = false);
    ~BagReader();
    BagReader(const BagReader&) = delete;
    BagReader& operator=(const BagReader&) = delete;

    std::size_t sweeps() const;   ///< messages on the cloud topic, bad ones included
    std::size_t skipped() const;  ///< bad messages skipped so far (both topics)
    const std::vector<StampedPose2>& odometry() const;
    /// The next sweep, nullopt after the last. Throws io::FileError "BAG: TOPIC message K: problem"
    /// for a malformed cloud.
    std::optional<CloudSweep> next();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct BagTopic {
    std::string type;
    std::size_t messages = 0;
};
/// Every topic of a bag with its message type and count. Throws io::FileError.
std::map<std::string, BagTopic> bag_topics(const std::filesystem::path& path);

/// Writes a bag (atomically: into PATH.active, renamed on close(); removed when destroyed
/// without close()). Stamps are seconds since the epoch (see kSimulatedEpoch_s for simulated time).
class BagWriter {
  public:
    explicit BagWriter(const std::filesystem::path& path);  ///< throws io::FileError
    ~BagWriter();
    BagWriter(const BagWriter&) = delete;
    BagWriter& operator=(const BagWriter&) = delete;

    void write_cloud(const std::string& topic, const PointCloud& cloud, double stamp_s,
                     const std::string& frame_id);
    void write_odometry(const std::string& topic, const Pose2& pose, double v_mps, double w_radps,
                        double stamp_s, const std::string& frame_id,
                        const std::string& child_frame_id);
    void write_costmap(const std::string& topic, const Costmap& costmap, double stamp_s,
                       const std::string& frame_id);
    void write_markers(const std::string& topic, const std::vector<ObjectEstimate>& objects,
                       const costmap::AffordanceParams& zones, double stamp_s,
                       const std::string& frame_id);
    /// On /tf, or /tf_static when `is_static`.
    void write_tf(const Isometry3& T_parent_child, double stamp_s, const std::string& parent,
                  const std::string& child, bool is_static = false);
    /// std_msgs/String (the object map as JSON).
    void write_text(const std::string& topic, const std::string& text, double stamp_s);
    void close();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// ros::Time has no time before 1970 and rosbag refuses time 0: simulated drives, which start at
/// 0 s, are written from this offset (2026-01-01T00:00:00Z).
constexpr double kSimulatedEpoch_s = 1767225600.0;

}  // namespace makeway::rosio
