#include "makeway/perception/accumulator.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace makeway::perception {

std::vector<std::string> AccumulatorParams::validate() const {
    std::vector<std::string> p;
    if (window < 1 || window > 100) p.push_back("window must be in [1, 100]");
    return p;
}

void KeyframeAccumulator::add(StampedSweep sweep) {
    const double stamp_s = sweep.stamp_s;
    const Isometry3 T_world_sensor_start = sweep.T_world_sensor_start;
    sweeps_.push_back({deskew_sweep(std::move(sweep), Isometry3::Identity(), params_.deskew),
                       stamp_s, T_world_sensor_start});
    while (static_cast<int>(sweeps_.size()) > params_.window) sweeps_.pop_front();
}

const PointCloud& KeyframeAccumulator::newest_world() const {
    static const PointCloud kEmpty;
    return sweeps_.empty() ? kEmpty : sweeps_.back().points_world;
}

PointCloud deskew_sweep(StampedSweep s, const Isometry3& T_target_world, bool deskew) {
    PointCloud c = std::move(s.points_sensor);
    const bool moved = !s.T_world_sensor_start.isApprox(s.T_world_sensor_end, 1e-12);
    const bool per_point = deskew && moved && c.time_s.size() == c.size() && s.duration_s > 0.0;
    // Points fired together share a time (a column of the scan): the pose is computed once per
    // distinct time, in float for the per-point product.
    float last_time = std::numeric_limits<float>::quiet_NaN();
    Eigen::Matrix3f R = (T_target_world * s.T_world_sensor_start).linear().cast<float>();
    Eigen::Vector3f t = (T_target_world * s.T_world_sensor_start).translation().cast<float>();
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (per_point && !(c.time_s[i] == last_time)) {
            last_time = c.time_s[i];
            const double alpha = std::clamp(c.time_s[i] / s.duration_s, 0.0, 1.0);
            const Isometry3 T =
                T_target_world * interpolate(s.T_world_sensor_start, s.T_world_sensor_end, alpha);
            R = T.linear().cast<float>();
            t = T.translation().cast<float>();
        }
        c.xyz[i] = R * c.xyz[i] + t;
    }
    return c;
}

PointCloud KeyframeAccumulator::keyframe(Isometry3* T_world_keyframe) const {
    PointCloud out;
    if (sweeps_.empty()) return out;
    const WorldSweep& newest = sweeps_.back();
    if (T_world_keyframe) *T_world_keyframe = newest.T_world_sensor_start;
    const Isometry3 T_keyframe_world = newest.T_world_sensor_start.inverse();
    const Eigen::Matrix3f R = T_keyframe_world.linear().cast<float>();
    const Eigen::Vector3f t = T_keyframe_world.translation().cast<float>();
    // Appended in place, into room for all of them, then moved into the keyframe's frame (a copy
    // of each sweep and the keyframe's regrowth were 7 % of ours' page faults in a navigation run).
    std::size_t total = 0;
    for (const WorldSweep& s : sweeps_) total += s.points_world.size();
    out.reserve(total, newest.points_world.fields());
    for (const WorldSweep& s : sweeps_) {
        const std::size_t first = out.size();
        out.append(s.points_world);
        for (std::size_t i = first; i < out.xyz.size(); ++i) out.xyz[i] = R * out.xyz[i] + t;
        const auto dt = static_cast<float>(s.stamp_s - newest.stamp_s);
        for (std::size_t i = first; i < out.time_s.size(); ++i) out.time_s[i] += dt;
    }
    return out;
}

}  // namespace makeway::perception
