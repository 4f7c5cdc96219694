#include "makeway/common/transforms.hpp"

#include <cmath>

#include "makeway/common/angles.hpp"

namespace makeway {

Isometry2 to_isometry(const Pose2& pose) {
    Isometry2 T = Isometry2::Identity();
    T.linear() = Eigen::Rotation2Dd(pose.yaw_rad).toRotationMatrix();
    T.translation() = Eigen::Vector2d(pose.x_m, pose.y_m);
    return T;
}

Pose2 to_pose2(const Isometry2& T) {
    return {T.translation().x(), T.translation().y(),
            wrap_angle(std::atan2(T.linear()(1, 0), T.linear()(0, 0)))};
}

Pose2 compose(const Pose2& a, const Pose2& b) { return to_pose2(to_isometry(a) * to_isometry(b)); }

Pose2 between(const Pose2& a, const Pose2& b) {
    return to_pose2(to_isometry(a).inverse() * to_isometry(b));
}

Pose2 interpolate(const Pose2& a, const Pose2& b, double s) {
    return {a.x_m + s * (b.x_m - a.x_m), a.y_m + s * (b.y_m - a.y_m),
            wrap_angle(a.yaw_rad + s * angle_diff(b.yaw_rad, a.yaw_rad))};
}

Isometry3 make_T_xyz_rpy(const Eigen::Vector3d& translation_m, double roll_rad, double pitch_rad,
                         double yaw_rad) {
    Isometry3 T = Isometry3::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = translation_m;
    return T;
}

Isometry3 make_T_xyz_yaw(const Eigen::Vector3d& translation_m, double yaw_rad) {
    Isometry3 T = Isometry3::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = translation_m;
    return T;
}

double yaw_of(const Eigen::Matrix3d& R) { return wrap_angle(std::atan2(R(1, 0), R(0, 0))); }

Pose2 project_to_plane(const Isometry3& T) {
    return {T.translation().x(), T.translation().y(), yaw_of(T)};
}

Isometry3 lift_to_3d(const Pose2& pose, double z_m) {
    return make_T_xyz_yaw({pose.x_m, pose.y_m, z_m}, pose.yaw_rad);
}

Isometry3 interpolate(const Isometry3& T_a, const Isometry3& T_b, double alpha) {
    const Eigen::Quaterniond q_a(T_a.linear());
    const Eigen::Quaterniond q_b(T_b.linear());
    Isometry3 T = Isometry3::Identity();
    T.linear() = q_a.slerp(alpha, q_b).toRotationMatrix();
    T.translation() = (1.0 - alpha) * T_a.translation() + alpha * T_b.translation();
    return T;
}

Isometry3 orthonormalized(const Isometry3& T) {
    Isometry3 out = T;
    out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
    return out;
}

}  // namespace makeway
