#include "makeway/tracking/occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace makeway::tracking {

bool ray_hits_aabb(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                   const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
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

ScanOcclusion::ScanOcclusion(const PointCloud& cloud, const Isometry3& T_world_sensor,
                             const OcclusionParams& params)
    : params_(params),
      T_sensor_world_(T_world_sensor.inverse()),
      sensor_z_world_(T_world_sensor.translation().z()) {
    bins_.resize(static_cast<std::size_t>(std::ceil(360.0 / params.scan_bin_deg)));
    for (const auto& p : cloud.xyz) {
        if (!p.allFinite()) continue;
        const double az = std::atan2(p.y(), p.x()) * 180.0 / std::numbers::pi + 180.0;
        const auto b =
            std::min(bins_.size() - 1, static_cast<std::size_t>(az / params.scan_bin_deg));
        bins_[b].push_back({p.head<2>().norm(), p.z()});
    }
}

bool ScanOcclusion::blocks(const Eigen::Vector3d& target_world, double z_lo_world,
                           double z_hi_world, double clear_m) const {
    const Eigen::Vector3d t = T_sensor_world_ * target_world;
    const double range = t.head<2>().norm();
    const double az = std::atan2(t.y(), t.x()) * 180.0 / std::numbers::pi + 180.0;
    const auto b = std::min(bins_.size() - 1, static_cast<std::size_t>(az / params_.scan_bin_deg));
    // The band in the sensor frame (the sensor is taken as level, as on a ground robot).
    // Returns near the object's base are skipped: they are the floor when ground was not removed.
    const double lo = z_lo_world + params_.scan_floor_clearance_m - sensor_z_world_,
                 hi = z_hi_world - sensor_z_world_;
    int in_front = 0;
    const double limit =
        range - clear_m - params_.scan_margin_m;  // nearer than the object itself can be
    for (const Return& r : bins_[b]) in_front += r.z_m >= lo && r.z_m <= hi && r.range_m < limit;
    return in_front >= params_.scan_min_points;
}

bool is_occluded(const Eigen::Vector3d& sensor, const OrientedBox& target,
                 const std::vector<OrientedBox>& others, const OcclusionParams& params,
                 const ScanOcclusion* scan) {
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
        if ((sensor.array() >= a.lo.array()).all() && (sensor.array() <= a.hi.array()).all())
            continue;
        boxes.push_back(a);
    }
    std::vector<Eigen::Vector3d> targets{target.centre_m};
    for (const auto& c : target.bev_corners()) {
        targets.emplace_back(target.centre_m.x() + params.shrink * (c.x() - target.centre_m.x()),
                             target.centre_m.y() + params.shrink * (c.y() - target.centre_m.y()),
                             target.centre_m.z());
    }
    const double radius =
        0.5 *
        target.size_m.head<2>().norm();  // the object's own returns lie within this of its centre
    int blocked = 0;
    for (const auto& t : targets) {
        blocked +=
            std::any_of(boxes.begin(), boxes.end(),
                        [&](const Aabb& a) { return ray_hits_aabb(sensor, t, a.lo, a.hi); }) ||
            (scan && scan->blocks(t, target.z_min_m(), target.z_max_m(),
                                  (t - target.centre_m).head<2>().norm() + radius));
    }
    return blocked >= params.blocked_fraction * static_cast<double>(targets.size());
}

}  // namespace makeway::tracking
