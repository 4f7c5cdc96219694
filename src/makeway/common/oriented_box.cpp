#include "makeway/common/oriented_box.hpp"

#include <cmath>

#include "makeway/common/angles.hpp"

namespace makeway {

std::array<Eigen::Vector2d, 4> OrientedBox::bev_corners() const {
    const double c = std::cos(yaw_rad);
    const double s = std::sin(yaw_rad);
    const Eigen::Vector2d ax(c * 0.5 * size_m.x(), s * 0.5 * size_m.x());   // half length
    const Eigen::Vector2d ay(-s * 0.5 * size_m.y(), c * 0.5 * size_m.y());  // half width
    const Eigen::Vector2d o = centre_m.head<2>();
    return {o - ax - ay, o + ax - ay, o + ax + ay, o - ax + ay};
}

std::array<Eigen::Vector3d, 8> OrientedBox::corners() const {
    const auto bev = bev_corners();
    std::array<Eigen::Vector3d, 8> out;
    for (int i = 0; i < 4; ++i) {
        out[i] = Eigen::Vector3d(bev[i].x(), bev[i].y(), z_min_m());
        out[i + 4] = Eigen::Vector3d(bev[i].x(), bev[i].y(), z_max_m());
    }
    return out;
}

bool OrientedBox::contains(const Eigen::Vector3d& p, double margin_m) const {
    const Eigen::Vector3d d = p - centre_m;
    const double c = std::cos(yaw_rad);
    const double s = std::sin(yaw_rad);
    const Eigen::Vector3d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
    return (local.cwiseAbs().array() <= (0.5 * size_m.array() + margin_m)).all();
}

OrientedBox OrientedBox::transformed(const Isometry3& T_to_from) const {
    OrientedBox out = *this;
    out.centre_m = T_to_from * centre_m;
    out.yaw_rad = wrap_angle(yaw_rad + yaw_of(T_to_from));
    return out;
}

bool OrientedBox::is_valid() const {
    return centre_m.allFinite() && size_m.allFinite() && std::isfinite(yaw_rad) &&
           (size_m.array() > 0.0).all();
}

}  // namespace makeway
