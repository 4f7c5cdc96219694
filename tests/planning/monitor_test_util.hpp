#pragma once
// What the collision monitor's tests share: the monitor sized for the simulator's robot (a
// Clearpath Jackal), and the distance from a point to that robot's footprint.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "makeway/common/angles.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/sim/robot.hpp"

namespace makeway::planning {

/// The monitor's defaults with the simulated robot's footprint, body, speeds and accelerations.
inline CollisionMonitorParams jackal() {
    CollisionMonitorParams p;
    p.apply_robot(sim::RobotParams{});
    return p;
}

/// Distance from a point to the simulated robot's footprint at `pose` (0 inside).
inline double footprint_distance(const Pose2& pose, const Eigen::Vector2d& p) {
    const sim::RobotParams r;
    const Eigen::Vector2d q = to_isometry(pose).inverse() * p;
    return Eigen::Vector2d(std::max(std::abs(q.x()) - 0.5 * r.length_m, 0.0),
                           std::max(std::abs(q.y()) - 0.5 * r.width_m, 0.0))
        .norm();
}

/// A round walker (centre `w`, `radius`) touching the simulated robot in `state`: the robot's speed
/// toward the contact point (the walker's surface toward the footprint's nearest point;
/// robot-caused above 0.05 m/s, as the benchmark judges it); nothing while they do not touch.
inline std::optional<double> speed_toward_walker(const sim::RobotState& state,
                                                 const Eigen::Vector2d& w, double radius) {
    const sim::RobotParams robot;
    if (footprint_distance(state.pose, w) > radius) return std::nullopt;
    const Eigen::Vector2d q = to_isometry(state.pose).inverse() * w;
    const Eigen::Vector2d near =
        to_isometry(state.pose) *
        Eigen::Vector2d(std::clamp(q.x(), -0.5 * robot.length_m, 0.5 * robot.length_m),
                        std::clamp(q.y(), -0.5 * robot.width_m, 0.5 * robot.width_m));
    const Eigen::Vector2d contact = w + radius * (near - w).normalized();
    return sim::speed_toward_contact(state.pose, state.v_mps, state.w_radps, contact,
                                     robot.length_m, robot.width_m);
}

/// The returns of a round walker (centre `w`, `radius`) on the side a sensor at `sensor` sees,
/// every 10 degrees, `z_m` up (a body).
inline PointCloud walker_sweep(const Eigen::Vector2d& w, double radius, const Pose2& sensor,
                               float z_m = 0.3f) {
    const Eigen::Vector2d toward = (Eigen::Vector2d(sensor.x_m, sensor.y_m) - w).normalized();
    PointCloud sweep;
    for (int a = 0; a < 36; ++a) {
        const double angle = a * kPi / 18;
        const Eigen::Vector2d q = w + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
        if ((q - w).dot(toward) > 0.0)
            sweep.xyz.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()), z_m);
    }
    return sweep;
}

/// What a VLP-32C 0.45 m up sees of 2D points at height z: nothing closer than `blind_m` to the
/// sensor (its lowest beam, -25 deg, reaches a 10 cm high part only from ~0.75 m).
inline PointCloud sweep_of(const std::vector<Eigen::Vector2d>& pts, const Pose2& sensor,
                           double blind_m, float z = 0.1f) {
    PointCloud c;
    for (const Eigen::Vector2d& p : pts) {
        if ((p - Eigen::Vector2d(sensor.x_m, sensor.y_m)).norm() < blind_m) continue;
        c.xyz.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), z);
    }
    return c;
}

/// A wall 3 m ahead of the origin (a return every 2 cm, 0.5 m up) and `extra` returns at that
/// height: a sweep for filter() with something new beside the robot.
inline PointCloud wall_ahead_and(const std::vector<Eigen::Vector2d>& extra = {}) {
    PointCloud c;
    for (double y = -1.0; y <= 1.0; y += 0.02)
        c.xyz.emplace_back(3.0f, static_cast<float>(y), 0.5f);
    for (const Eigen::Vector2d& q : extra)
        c.xyz.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()), 0.5f);
    return c;
}

}  // namespace makeway::planning
