#pragma once
// The front end of the online system: the pose of every sweep (LiDAR odometry fused with the wheel
// odometry from the start pose, or the wheel odometry alone), and every `keyframe.every` sweeps a
// keyframe (the last `window` sweeps de-skewed and accumulated into the newest sweep's frame,
// ground plane by RANSAC at the first keyframe, ground and ceiling removed). The Pipeline runs it
// on label-free sweeps; the detector's dataset runs the very same code on labelled ones, so that
// training and evaluation see the pipeline's keyframes.
#include <optional>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/odometry/lidar_odometry.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace makeway::pipeline {

/// One LiDAR sweep as a robot receives it.
struct Sweep {
    PointCloud
        points_sensor;  ///< in the sensor frame of each point's firing time; time_s since stamp_s
    double stamp_s = 0.0;  ///< sweep start [s]
    double duration_s = 0.1;
    /// Wheel odometry of the base (its own drifting frame) at the sweep's start and end. Absent:
    /// the robot is taken as standing still since the last reading.
    std::optional<Pose2> odometry_start, odometry_end;
};

struct FrontEndKeyframe {
    Isometry3 T_world_keyframe = Isometry3::Identity();  ///< estimated: the newest sweep's start
    PreparedKeyframe prepared;
    double accumulate_ms = 0.0, ground_ms = 0.0;
};

struct FrontEndResult {
    Isometry3 T_world_sensor_start = Isometry3::Identity();  ///< estimated
    Isometry3 T_world_sensor_end = Isometry3::Identity();
    Pose2 pose;               ///< the base at the sweep's end, estimated
    PointCloud points_world;  ///< the sweep de-skewed into the world frame
    std::optional<FrontEndKeyframe> keyframe;
    double deskew_ms = 0.0;    ///< pose and de-skewing of this sweep (the odometry included)
    double odometry_ms = 0.0;  ///< the LiDAR odometry's registration alone
    std::optional<odometry::OdometryResult> odometry;  ///< with lidar_odometry
};

class FrontEnd {
  public:
    /// `params.validate()` is the caller's (the Pipeline checks it once).
    FrontEnd(const SystemParams& params, const Pose2& start_pose);
    /// Channels are kept as given (the Pipeline strips the simulator's before).
    FrontEndResult add(Sweep sweep);

  private:
    Isometry3 T_world_sensor_at(const Pose2& odometry) const;

    SystemParams params_;
    Pose2 start_pose_;
    perception::KeyframeAccumulator accumulator_;
    std::optional<odometry::LidarOdometry> lidar_odometry_;
    std::optional<Isometry2> T_world_odom_;  ///< fixed by the first odometry reading
    Pose2 last_odometry_;
    std::optional<perception::GroundPlaneResult> ground_;  ///< fitted once, at the first keyframe
    std::size_t sweeps_ = 0;
};

}  // namespace makeway::pipeline
