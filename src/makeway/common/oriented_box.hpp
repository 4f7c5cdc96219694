#pragma once
// Oriented 3D box of an object standing on the ground: rotation about z only.
#include <array>

#include "makeway/common/transforms.hpp"

namespace makeway {

struct OrientedBox {
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< geometric centre (not the bottom)
    Eigen::Vector3d size_m = Eigen::Vector3d::Zero();    ///< length (box x), width (box y), height
    double yaw_rad = 0.0;                                ///< heading of the box x axis about z

    /// Pose of the box frame (origin at the centre, x along the length).
    Isometry3 T_frame_box() const { return make_T_xyz_yaw(centre_m, yaw_rad); }
    double volume_m3() const { return size_m.prod(); }
    double z_min_m() const { return centre_m.z() - 0.5 * size_m.z(); }
    double z_max_m() const { return centre_m.z() + 0.5 * size_m.z(); }

    /// Footprint corners, counter-clockwise.
    std::array<Eigen::Vector2d, 4> bev_corners() const;
    /// The 8 corners: the 4 bottom ones (counter-clockwise), then the 4 top ones.
    std::array<Eigen::Vector3d, 8> corners() const;
    /// Whether p lies inside the box grown by margin_m on every side.
    bool contains(const Eigen::Vector3d& p, double margin_m = 0.0) const;
    /// The same box seen from another frame: T_to_from * box. Roll and pitch of T are ignored.
    OrientedBox transformed(const Isometry3& T_to_from) const;
    /// Sizes positive and every value finite.
    bool is_valid() const;
};

}  // namespace makeway
