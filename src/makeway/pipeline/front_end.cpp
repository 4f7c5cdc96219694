#include "makeway/pipeline/front_end.hpp"

#include "makeway/common/stopwatch.hpp"

namespace makeway::pipeline {

FrontEnd::FrontEnd(const SystemParams& params, const Pose2& start_pose)
    : params_(params),
      start_pose_(start_pose),
      accumulator_({.window = params.keyframe.window, .deskew = params.keyframe.deskew}) {
    if (params.lidar_odometry_enabled)
        lidar_odometry_.emplace(params.lidar_odometry, params.T_base_sensor, start_pose);
}

Isometry3 FrontEnd::T_world_sensor_at(const Pose2& odometry) const {
    return lift_to_3d(to_pose2(*T_world_odom_ * to_isometry(odometry))) * params_.T_base_sensor;
}

FrontEndResult FrontEnd::add(Sweep sweep) {
    FrontEndResult out;
    const SteadyClock::time_point t0 = SteadyClock::now();
    // Pose: the LiDAR odometry's, or the start pose plus the wheel odometry's motion since the
    // first reading (the odometry frame's origin is wherever the robot was switched on). Start and
    // end poses let every point be de-skewed by its own time.
    if (lidar_odometry_) {
        // LiDAR odometry: the sweep registered against the local map with the wheels as prior.
        const SteadyClock::time_point t_odo = SteadyClock::now();
        const bool wheels = sweep.odometry_start && sweep.odometry_end;
        out.odometry =
            lidar_odometry_->register_sweep(sweep.points_sensor, sweep.stamp_s, sweep.duration_s,
                                            wheels ? sweep.odometry_start : std::nullopt,
                                            wheels ? sweep.odometry_end : std::nullopt);
        out.odometry_ms = ms_since(t_odo);
        out.T_world_sensor_start = out.odometry->T_world_sensor_start;
        out.T_world_sensor_end = out.odometry->T_world_sensor_end;
        out.pose = out.odometry->pose;
    } else {
        const Pose2 odom_start = sweep.odometry_start.value_or(last_odometry_);
        const Pose2 odom_end = sweep.odometry_end.value_or(odom_start);
        if (!T_world_odom_)
            T_world_odom_ = to_isometry(start_pose_) * to_isometry(odom_start).inverse();
        last_odometry_ = odom_end;
        out.T_world_sensor_start = T_world_sensor_at(odom_start);
        out.T_world_sensor_end = T_world_sensor_at(odom_end);
        out.pose = to_pose2(*T_world_odom_ * to_isometry(odom_end));
    }
    accumulator_.add({std::move(sweep.points_sensor), sweep.stamp_s, sweep.duration_s,
                      out.T_world_sensor_start, out.T_world_sensor_end});
    out.points_world = accumulator_.newest_world();
    out.deskew_ms = ms_since(t0);
    if (!accumulator_.full() || sweeps_++ % static_cast<std::size_t>(params_.keyframe.every) != 0)
        return out;

    // Keyframe: the window in the newest sweep's frame, then the ground plane (fitted once: the
    // sensor is rigid on the robot) and the ground and ceiling removed.
    FrontEndKeyframe kf;
    SteadyClock::time_point t = SteadyClock::now();
    const PointCloud raw = accumulator_.keyframe(&kf.T_world_keyframe);
    kf.accumulate_ms = ms_since(t);
    t = SteadyClock::now();
    kf.prepared = prepare_keyframe(raw, params_.keyframe, ground_ ? &*ground_ : nullptr);
    if (kf.prepared.ground.found) ground_ = kf.prepared.ground;
    kf.ground_ms = ms_since(t);
    out.keyframe = std::move(kf);
    return out;
}

}  // namespace makeway::pipeline
