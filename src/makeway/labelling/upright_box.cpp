#include "makeway/labelling/upright_box.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "makeway/common/angles.hpp"

namespace makeway::labelling {

OrientedBox upright_pca_box(const std::vector<Eigen::Vector3d>& points,
                            std::optional<double> floor_z_m) {
    OrientedBox box;
    if (points.empty()) return box;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector3d& p : points) mean += p.head<2>();
    mean /= static_cast<double>(points.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector3d& p : points) {
        const Eigen::Vector2d d = p.head<2>() - mean;
        cov += d * d.transpose();
    }
    double yaw = 0.0;
    if (cov.trace() > 1e-12) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
        const Eigen::Vector2d axis = eig.eigenvectors().col(1);  // largest eigenvalue last
        yaw = std::atan2(axis.y(), axis.x());
        if (yaw <= -kPi / 2) yaw += kPi;
        if (yaw > kPi / 2) yaw -= kPi;
    }
    const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
    constexpr double kInf = std::numeric_limits<double>::infinity();
    Eigen::Vector3d lo(kInf, kInf, kInf), hi = -lo;
    for (const Eigen::Vector3d& p : points) {
        const Eigen::Vector3d local(p.head<2>().dot(ex), p.head<2>().dot(ey), p.z());
        lo = lo.cwiseMin(local);
        hi = hi.cwiseMax(local);
    }
    if (floor_z_m && *floor_z_m < lo.z()) lo.z() = *floor_z_m;
    const Eigen::Vector3d mid = 0.5 * (lo + hi);
    box.centre_m << mid.x() * ex + mid.y() * ey, mid.z();
    box.size_m = hi - lo;
    box.yaw_rad = yaw;
    return box;
}

}  // namespace makeway::labelling
