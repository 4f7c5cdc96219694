#include "makeway/sim/sequence.hpp"

#include <cmath>

#include "makeway/common/angles.hpp"

namespace makeway::sim {

std::vector<std::string> SequenceParams::validate() const {
    std::vector<std::string> p;
    for (const auto& m : lidar.validate()) p.push_back("lidar." + m);
    for (const auto& m : robot.validate()) p.push_back("robot." + m);
    for (const auto& m : odometry.validate()) p.push_back("odometry." + m);
    if (!(physics_rate_hz >= lidar.rate_hz && physics_rate_hz <= 10000))
        p.push_back("physics_rate_hz must be in [lidar rate, 10000]");
    if (!(lookahead_m > 0.05 && lookahead_m < 5.0)) p.push_back("lookahead_m must be in (0.05, 5)");
    if (!(goal_tolerance_m > 0.0 && goal_tolerance_m < 2.0))
        p.push_back("goal_tolerance_m must be in (0, 2)");
    return p;
}

SequenceSimulator::SequenceSimulator(const Scene& scene, std::vector<Eigen::Vector2d> route,
                                     const SequenceParams& params)
    : scene_(scene),
      route_(std::move(route)),
      params_(params),
      world_(scene, models_of(scene)),
      checker_(scene, world_.models(), params.robot),
      odometry_(scene.start, params.odometry, params.seed) {
    state_.pose = scene.start;
    if (!route_.empty()) {  // face the first leg
        const Eigen::Vector2d next = route_.size() > 1 ? route_[1] : route_[0];
        state_.pose.yaw_rad = std::atan2(next.y() - scene.start.y_m, next.x() - scene.start.x_m);
    }
    start_pose_ = state_.pose;
    odometry_ = WheelOdometry(start_pose_, params.odometry,
                              params.seed);  // the odometry frame is the world at the start
}

VelocityCommand SequenceSimulator::pure_pursuit(const RobotState& state) {
    if (route_.empty() || reached_goal_) return {};
    const Eigen::Vector2d p(state.pose.x_m, state.pose.y_m);
    // Advance along the route past points already within the lookahead.
    while (route_index_ + 1 < route_.size() &&
           (route_[route_index_] - p).norm() < params_.lookahead_m)
        ++route_index_;
    const Eigen::Vector2d target = route_[route_index_];
    const double dist_goal = (route_.back() - p).norm();
    if (route_index_ + 1 == route_.size() && dist_goal < params_.goal_tolerance_m) {
        reached_goal_ = true;
        return {};
    }
    const double alpha =
        angle_diff(std::atan2(target.y() - p.y(), target.x() - p.x()), state.pose.yaw_rad);
    const double max_v = params_.robot.max_v_mps;
    if (std::abs(alpha) > deg_to_rad(60))
        return {0.0, std::copysign(0.8 * params_.robot.max_w_radps, alpha)};
    double v = max_v * std::clamp(1.0 - std::abs(alpha) / (kPi / 2), 0.2, 1.0);
    if (route_index_ + 1 == route_.size()) v = std::min(v, 0.8 * dist_goal + 0.1);
    const double ld = std::max((target - p).norm(), 1e-3);
    return {v, 2.0 * v * std::sin(alpha) / ld};
}

SimFrame SequenceSimulator::next() {
    SimFrame f;
    f.index = frame_index_;
    const double period = params_.lidar.sweep_duration_s();
    f.stamp_s = frame_index_ * period;
    f.true_pose = state_.pose;
    f.odometry_pose = odometry_.pose();
    f.objects = object_states_at(scene_, world_.models(), f.stamp_s);
    for (const Walker& w : scene_.walkers) f.people_m.push_back(walker_position_at(w, f.stamp_s));
    trajectory_.push_back(state_.pose);

    // Drive through the sweep period first, keeping the poses to interpolate the sensor motion.
    const int steps = std::max(1, static_cast<int>(std::lround(params_.physics_rate_hz * period)));
    const double dt = period / steps;
    std::vector<Pose2> poses{state_.pose};
    for (int i = 0; i < steps; ++i) {
        const VelocityCommand cmd = pure_pursuit(state_);
        const RobotState before = state_;
        state_ = step_diff_drive(state_, cmd, dt, params_.robot);
        odometry_.update(before.pose, state_.pose);
        poses.push_back(state_.pose);
        f.collided |= checker_.collides(state_.pose, f.stamp_s + (i + 1) * dt);
    }
    f.odometry_end_pose = odometry_.pose();
    const double t0 = f.stamp_s;
    const PoseAtTime T_world_sensor_at =
        sensor_pose_along(std::move(poses), t0, dt, params_.robot.T_robot_sensor());
    f.T_world_sensor = T_world_sensor_at(t0);
    f.points_sensor = simulate_sweep(world_, params_.lidar, T_world_sensor_at, t0, params_.seed,
                                     static_cast<std::uint64_t>(frame_index_), &f.sweep);
    ++frame_index_;
    return f;
}

}  // namespace makeway::sim
