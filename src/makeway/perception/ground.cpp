#include "makeway/perception/ground.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/voxel_thin.hpp"
#include "makeway/perception/param_tables.hpp"

namespace makeway::perception {

std::vector<std::string> GroundPlaneParams::validate() const {
    return ground_plane_table().problems(*this);
}

std::vector<std::string> GroundFilterParams::validate() const {
    return ground_filter_table().problems(*this);
}

GroundPlaneResult fit_ground_plane(const PointCloud& cloud, const GroundPlaneParams& params) {
    GroundPlaneResult best;
    std::vector<Eigen::Vector3d> pts;
    pts.reserve(cloud.size());
    for (const auto& p : cloud.xyz) {
        if (p.allFinite()) pts.push_back(p.cast<double>());
    }
    if (pts.size() < 3) {
        best.reason = "fewer than 3 finite points";
        return best;
    }
    // Hypotheses are scored on one point per voxel, so a plane's score is its area, not its point
    // count: a spinning LiDAR packs its beams near the horizon, and the dense bands they draw on
    // nearby walls, joined with the first floor ring, otherwise make a tilted "plane" with more
    // points than the floor.
    const std::vector<Eigen::Vector3d> cells =
        params.voxel_m > 0.0 ? voxel_thin(pts, params.voxel_m) : pts;
    Rng rng = make_rng(params.seed, 31);
    const double cos_tilt = std::cos(deg_to_rad(params.max_tilt_deg));
    const auto n_cells = static_cast<std::int64_t>(cells.size());
    for (int it = 0; it < params.iterations; ++it) {
        const Eigen::Vector3d& a = cells[uniform_int(rng, 0, n_cells - 1)];
        const Eigen::Vector3d& b = cells[uniform_int(rng, 0, n_cells - 1)];
        const Eigen::Vector3d& c = cells[uniform_int(rng, 0, n_cells - 1)];
        Eigen::Vector3d n = (b - a).cross(c - a);
        if (n.norm() < 1e-9) continue;
        n.normalize();
        if (n.z() < 0) n = -n;
        if (n.z() < cos_tilt) continue;
        const double d = -n.dot(a);
        if (d < params.min_sensor_height_m) continue;  // d is the sensor's height above the plane
        std::size_t inliers = 0;
        for (const auto& p : cells) inliers += std::abs(n.dot(p) + d) < params.inlier_distance_m;
        // The ground is the largest plane; among ties, the lowest (a table top has fewer points).
        if (inliers > best.inliers || (inliers == best.inliers && d > best.offset)) {
            best.inliers = inliers;
            best.normal = n;
            best.offset = d;
        }
    }
    if (best.inliers < params.min_inliers) {
        best.reason = "no plane with at least " + std::to_string(params.min_inliers) +
                      " occupied voxels within " + std::to_string(params.max_tilt_deg) +
                      " deg of horizontal";
        best.inliers = 0;
        return best;
    }
    // Least-squares refinement: the smallest principal direction of the inliers.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> in;
    for (const auto& p : pts) {
        if (std::abs(best.normal.dot(p) + best.offset) < params.inlier_distance_m) in.push_back(p);
    }
    for (const auto& p : in) mean += p;
    mean /= static_cast<double>(in.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : in) cov += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Vector3d n = eig.eigenvectors().col(0);
    if (n.z() < 0) n = -n;
    best.normal = n;
    best.offset = -n.dot(mean);
    best.inliers = in.size();
    best.found = true;
    return best;
}

PointCloud remove_ground_and_ceiling(const PointCloud& cloud, const GroundPlaneResult& ground,
                                     const GroundFilterParams& params) {
    if (!ground.found) return cloud;
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.xyz[i].allFinite()) continue;
        const double h = ground.height_of(cloud.xyz[i].cast<double>());
        if (h > params.ground_band_m && h < params.ceiling_height_m) keep.push_back(i);
    }
    return cloud.select(keep);
}

}  // namespace makeway::perception
