#include "makeway/odometry/voxel_map.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "makeway/common/floor_index.hpp"

namespace makeway::odometry {

Eigen::Vector3i VoxelMap::key(const Eigen::Vector3d& p) const {
    // floor(p / voxel) per axis, clamped one short of int's ends (a damaged cloud's coordinate
    // beyond 5e8 m would make the cast undefined, and nearest() steps one voxel either side):
    // every such point shares the edge voxel.
    constexpr std::int64_t kLow = std::numeric_limits<int>::min() + 1,
                           kHigh = std::numeric_limits<int>::max() - 1;
    Eigen::Vector3i k;
    for (int a = 0; a < 3; ++a)
        k(a) = static_cast<int>(std::clamp(floor_index(p(a), params_.voxel_m), kLow, kHigh));
    return k;
}

void VoxelMap::fit_plane(Voxel& v) const {
    v.shape = VoxelShape::kUnknown;
    if (static_cast<int>(v.points.size()) < params_.min_points_for_plane) return;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : v.points) mean += p;
    mean /= static_cast<double>(v.points.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : v.points) cov += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    // Eigenvalues ascending: flat when the smallest spread is small against the middle one (a
    // line of points, e.g. one scan ring on a wall, has no plane: its middle spread is tiny too).
    const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
    const double share = params_.planarity * params_.planarity;  // eigenvalues are spreads squared
    if (ev(2) <= 1e-8) return;                                   // all points in one place
    if (ev(1) <= share * ev(2)) {
        v.shape = VoxelShape::kLine;
        v.axis = eig.eigenvectors().col(2).normalized();
    } else if (ev(0) <= share * ev(1)) {
        v.shape = VoxelShape::kPlane;
        v.axis = eig.eigenvectors().col(0).normalized();
    } else {
        v.shape = VoxelShape::kBlob;
    }
}

void VoxelMap::add(const std::vector<Eigen::Vector3d>& points_world) {
    std::vector<Eigen::Vector3i> changed;
    for (const auto& p : points_world) {
        if (!p.allFinite()) continue;
        const Eigen::Vector3i k = key(p);
        auto it = voxels_.find(k);
        if (it == voxels_.end()) {
            it = voxels_.emplace(k, Voxel{}).first;
            it.value().first = p;
        }
        Voxel& v = it.value();
        if (static_cast<int>(v.points.size()) >= params_.max_points_per_voxel) continue;
        v.points.push_back(p);
        for (int a = 0; a < 3; ++a) {
            // Rounded outward, so that the box in float holds every point in double (a
            // coordinate beyond float's range, from a damaged cloud, opens the box to infinity).
            constexpr double kMax = std::numeric_limits<float>::max();
            float lo = static_cast<float>(std::clamp(p(a), -kMax, kMax)), hi = lo;
            if (static_cast<double>(lo) > p(a))
                lo = std::nextafter(lo, -std::numeric_limits<float>::infinity());
            if (static_cast<double>(hi) < p(a))
                hi = std::nextafter(hi, std::numeric_limits<float>::infinity());
            v.low(a) = std::min(v.low(a), lo);
            v.high(a) = std::max(v.high(a), hi);
        }
        changed.push_back(k);
    }
    std::sort(
        changed.begin(), changed.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        });
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    for (const auto& k : changed) fit_plane(voxels_.find(k).value());
}

void VoxelMap::keep_within(const Eigen::Vector3d& centre, double radius_m) {
    const double r2 = radius_m * radius_m;
    for (auto it = voxels_.begin(); it != voxels_.end();) {
        const Eigen::Vector3d d = it->second.first - centre;
        if (d.head<2>().squaredNorm() > r2) {
            it = voxels_.erase(it);
        } else {
            ++it;
        }
    }
}

std::optional<MapMatch> VoxelMap::nearest(const Eigen::Vector3d& query,
                                          double max_distance_m) const {
    const Eigen::Vector3i k = key(query);
    double best = max_distance_m * max_distance_m;
    const Voxel* best_voxel = nullptr;
    const Eigen::Vector3d* best_point = nullptr;
    // A neighbour's points are read only when the box around them is not farther than the best
    // match so far (a voxel of a wall holds a thin slab of it): with a relative margin far above
    // the rounding of either distance, so a skipped voxel never held the point the full search
    // would return.
    const auto box_far = [&](const Voxel& v) {
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double g = std::max({static_cast<double>(v.low(a)) - query(a),
                                       query(a) - static_cast<double>(v.high(a)), 0.0});
            d2 += g * g;
        }
        return d2 > best * (1.0 + 1e-9);
    };
    const auto search = [&](const Eigen::Vector3i& at, bool neighbour) {
        const auto it = voxels_.find(at);
        if (it == voxels_.end() || (neighbour && box_far(it->second))) return;
        for (const auto& p : it->second.points) {
            const double d2 = (p - query).squaredNorm();
            if (d2 < best) {
                best = d2;
                best_voxel = &it->second;
                best_point = &p;
            }
        }
    };
    // The query's own voxel first: its nearest point is usually within a few centimetres, and
    // with that bound most neighbours are never looked up (before, in grid order, the first 13
    // were searched with the full correspondence distance as the bound).
    search(k, false);
    // How far the query lies inside its voxel: a neighbour whose nearest face is farther than the
    // best match so far cannot hold a closer point, and is not looked up.
    const Eigen::Vector3d low = query - k.cast<double>() * params_.voxel_m;
    const Eigen::Vector3d high = Eigen::Vector3d::Constant(params_.voxel_m) - low;
    const auto gap2 = [&](int d, int axis) {
        return d < 0 ? low(axis) * low(axis) : d > 0 ? high(axis) * high(axis) : 0.0;
    };
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                if ((dx | dy | dz) == 0 || gap2(dx, 0) + gap2(dy, 1) + gap2(dz, 2) >= best)
                    continue;
                search(Eigen::Vector3i(k.x() + dx, k.y() + dy, k.z() + dz), true);
            }
        }
    }
    if (!best_point) return std::nullopt;
    return MapMatch{*best_point, best_voxel->shape, best_voxel->axis, std::sqrt(best)};
}

std::vector<Eigen::Vector3d> VoxelMap::points() const {
    std::vector<Eigen::Vector3d> out;
    for (const auto& [k, v] : voxels_) out.insert(out.end(), v.points.begin(), v.points.end());
    return out;
}

std::size_t VoxelMap::num_points() const {
    std::size_t n = 0;
    for (const auto& [k, v] : voxels_) n += v.points.size();
    return n;
}

}  // namespace makeway::odometry
