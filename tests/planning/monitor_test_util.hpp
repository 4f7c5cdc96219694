#pragma once
// What the collision monitor's tests share: the monitor sized for the simulator's robot (a
// Clearpath Jackal), and the distance from a point to that robot's footprint.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

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

}  // namespace makeway::planning
