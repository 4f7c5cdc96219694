#pragma once
// The robot, described once: its footprint, what it can hit in height, its speed and acceleration
// limits, and where its LiDAR sits. The simulator drives this robot (sim::RobotParams is this
// type) and the online system plans, guards and maps for it (pipeline::apply_robot): one YAML
// section, `robot:`, feeds both, so the robot the benchmark moves is the robot the system believes
// it has. Defaults: a Clearpath Jackal with a VLP-32C on a mount, as in the paper.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "makeway/common/robot_body.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway {

struct RobotDescription {
    double length_m = 0.508;      ///< footprint along x (a rectangle centred on the base)
    double width_m = 0.430;       ///< footprint along y
    double body_height_m = 0.50;  ///< top of the robot with its sensor: collisions below this
    double ground_clearance_m =
        0.02;  ///< parts lower than this are rolled over (common/robot_body.hpp)
    double lidar_height_m = 0.45;  ///< LiDAR optical centre above the floor, over the base's centre
    double max_v_mps = 0.75;       ///< top speed, as in the paper
    double max_w_radps = 2.0;
    double max_acc_mps2 = 1.0;
    double max_ang_acc_radps2 = 3.0;

    double inscribed_radius_m() const { return 0.5 * std::min(length_m, width_m); }
    double circumscribed_radius_m() const { return 0.5 * std::hypot(length_m, width_m); }
    /// What the robot can hit, in height: shared with the costmap's obstacle layer.
    BodyHeights body() const { return {ground_clearance_m, body_height_m}; }
    /// The sensor on the base (the extrinsics), when none are given: lidar_height_m above its
    /// centre.
    Isometry3 T_robot_sensor() const { return make_T_xyz_yaw({0.0, 0.0, lidar_height_m}, 0.0); }
    /// Every problem, one per entry ("length_m must be in (0.05, 5)").
    std::vector<std::string> validate() const;
};

}  // namespace makeway
