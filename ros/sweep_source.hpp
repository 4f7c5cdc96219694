#pragma once
// Where `makeway run` (and tests) get sweeps: a folder of cloud files (with TUM wheel odometry or
// external poses, line k for sweep k) or a ROS 1 bag (odometry messages interpolated at each
// sweep's start and end). Each gives sweeps as a robot has them, in time order.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/point_cloud_io.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "ros/bag_io.hpp"

namespace makeway::rosio {

struct SourceSweep {
    PointCloud points;  ///< sensor frame; time_s since stamp_s when timed
    double stamp_s = 0.0;
    double duration_s = 0.1;
    bool timed = false;
    /// The base's pose in the odometry frame (wheels) or in the world (external poses), at the
    /// sweep's start and end; absent without either.
    std::optional<Pose2> pose_start, pose_end;
    std::string file;  ///< where it came from, for errors: the cloud file or the bag ...
    std::string item;  ///< ... and within a bag, "TOPIC message K" (empty for files)
};

struct SourceOptions {
    std::string clouds, bag;
    std::string odometry;  ///< TUM of the base, line k at sweep k's start (folders only)
    std::string
        poses;  ///< TUM of T_world_sensor at sweep starts (external poses; skips the odometry)
    BagTopics topics;
    bool external_poses = false;  ///< bags: the odometry topic holds the external poses
    double rate_hz = 10.0;        ///< sweep rate when nothing gives stamps
    io::NonFinitePolicy non_finite = io::NonFinitePolicy::kReject;
    /// Bags: messages that do not deserialise or hold nonsense, and sweeps whose stamp does not
    /// follow the previous one, are skipped and counted instead of ending the run.
    bool skip_bad_messages = false;
    Isometry3 T_base_sensor =
        Isometry3::Identity();  ///< to turn external sensor poses into base poses
};

class SweepSource {
  public:
    virtual ~SweepSource() = default;
    virtual std::size_t size() const = 0;
    /// nullopt after the last. Throws io::FileError naming the file (and message) on bad input.
    virtual std::optional<SourceSweep> next() = 0;
    /// The base's first pose (odometry or external), when there is one.
    virtual std::optional<Pose2> first_pose() const = 0;
    virtual std::string describe() const = 0;
    /// Bad messages skipped so far (skip_bad_messages).
    virtual std::size_t skipped() const { return 0; }
};

/// Checks everything that can be checked before the first sweep (folders exist and hold sweeps,
/// pose files cover them, the bag has the topics); throws io::FileError.
std::unique_ptr<SweepSource> open_sweep_source(const SourceOptions& options);

/// The pose at time t by linear interpolation (yaw the short way), nullopt outside [first, last]
/// (1 ms of slack at either end).
std::optional<Pose2> interpolate_at(const std::vector<StampedPose2>& poses, double t_s);

}  // namespace makeway::rosio
