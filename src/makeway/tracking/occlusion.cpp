#include "makeway/tracking/occlusion.hpp"

#include <algorithm>
#include <cmath>

namespace makeway::tracking {

bool ray_hits_aabb(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const Eigen::Vector3d d = to - from;
    double t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (from[a] < lo[a] || from[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - from[a]) / d[a], tb = (hi[a] - from[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return t0 > 0.0 && t0 < 1.0;  // entered between the ends
}

bool is_occluded(const Eigen::Vector3d& sensor, const OrientedBox& target, const std::vector<OrientedBox>& others,
                 const OcclusionParams& params) {
    struct Aabb {
        Eigen::Vector3d lo, hi;
    };
    std::vector<Aabb> boxes;
    for (const OrientedBox& b : others) {
        Aabb a{Eigen::Vector3d::Constant(1e300), Eigen::Vector3d::Constant(-1e300)};
        for (const auto& c : b.bev_corners()) {
            a.lo.head<2>() = a.lo.head<2>().cwiseMin(c);
            a.hi.head<2>() = a.hi.head<2>().cwiseMax(c);
        }
        a.lo.z() = b.z_min_m();
        a.hi.z() = b.z_max_m();
        if ((sensor.array() >= a.lo.array()).all() && (sensor.array() <= a.hi.array()).all()) continue;
        boxes.push_back(a);
    }
    std::vector<Eigen::Vector3d> targets{target.centre_m};
    for (const auto& c : target.bev_corners()) {
        targets.emplace_back(target.centre_m.x() + params.shrink * (c.x() - target.centre_m.x()),
                             target.centre_m.y() + params.shrink * (c.y() - target.centre_m.y()), target.centre_m.z());
    }
    int blocked = 0;
    for (const auto& t : targets) {
        blocked += std::any_of(boxes.begin(), boxes.end(), [&](const Aabb& a) { return ray_hits_aabb(sensor, t, a.lo, a.hi); });
    }
    return blocked >= params.blocked_fraction * static_cast<double>(targets.size());
}

}  // namespace makeway::tracking
