#pragma once
// SE(2)/SE(3) helpers on Eigen. Transforms are named T_<to>_<from>: p_world = T_world_sensor *
// p_sensor.
#include <Eigen/Geometry>

namespace makeway {

using Isometry2 = Eigen::Isometry2d;
using Isometry3 = Eigen::Isometry3d;

/// Planar pose (x, y [m], yaw [rad]); the value type the planner and costmap use.
struct Pose2 {
    double x_m = 0.0;
    double y_m = 0.0;
    double yaw_rad = 0.0;
};

Isometry2 to_isometry(const Pose2& pose);
Pose2 to_pose2(const Isometry2& T);

/// a then b (b in a's frame), and the motion from a to b in a's frame.
Pose2 compose(const Pose2& a, const Pose2& b);
Pose2 between(const Pose2& a, const Pose2& b);
/// Between two planar poses: x, y linear, yaw along the shorter turn; s in [0, 1].
Pose2 interpolate(const Pose2& a, const Pose2& b, double s);

/// SE(3) from a translation [m] and a rotation about z [rad] (roll = pitch = 0).
Isometry3 make_T_xyz_yaw(const Eigen::Vector3d& translation_m, double yaw_rad);
/// x y z [m], then roll pitch yaw [rad] applied as R = Rz(yaw) Ry(pitch) Rx(roll) (ROS's static
/// transform order): how extrinsics are given on the command line and as the node's parameter.
Isometry3 make_T_xyz_rpy(const Eigen::Vector3d& translation_m, double roll_rad, double pitch_rad,
                         double yaw_rad);

/// Heading of the x axis projected onto the xy plane [rad], in [-pi, pi).
double yaw_of(const Eigen::Matrix3d& R);
inline double yaw_of(const Isometry3& T) { return yaw_of(T.linear()); }

/// Drops z, roll and pitch: the planar part of an SE(3) pose.
Pose2 project_to_plane(const Isometry3& T);

/// Lifts a planar pose to SE(3) at height z [m].
Isometry3 lift_to_3d(const Pose2& pose, double z_m = 0.0);

/// Interpolates between two poses: linear in translation, slerp in rotation; alpha in [0, 1].
Isometry3 interpolate(const Isometry3& T_a, const Isometry3& T_b, double alpha);

/// Re-orthonormalises the rotation part (accumulated products drift off SO(3)).
Isometry3 orthonormalized(const Isometry3& T);

}  // namespace makeway
