#include "makeway/perception/levelling.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace makeway::perception {

Isometry3 level_frame(const Eigen::Vector4d& plane_sensor, double height_m) {
    const Eigen::Vector3d n = plane_sensor.head<3>();
    const double d = plane_sensor(3);
    if (!plane_sensor.allFinite() || std::abs(n.norm() - 1.0) > 0.05 || !(d > 0.0 && d < 10.0) ||
        !std::isfinite(height_m))
        return Isometry3::Identity();
    const Eigen::Vector3d up = n.normalized();
    Isometry3 T = Isometry3::Identity();
    // FromTwoVectors is the smallest rotation: a level sensor's frame keeps its heading.
    T.linear() =
        Eigen::Quaterniond::FromTwoVectors(up, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // The floor (up . p = -d) lands at z = -d; shifted so that it lies at -height_m.
    T.translation() = Eigen::Vector3d(0.0, 0.0, d - height_m);
    return T;
}

std::optional<Isometry3> level_frame_if(const std::optional<Eigen::Vector4d>& plane_sensor,
                                        double height_m) {
    if (!plane_sensor || !(height_m > 0.0)) return std::nullopt;
    return level_frame(*plane_sensor, height_m);
}

}  // namespace makeway::perception
