#include "makeway/perception/accumulator.hpp"

#include <algorithm>

namespace makeway::perception {

std::vector<std::string> AccumulatorParams::validate() const {
    std::vector<std::string> p;
    if (window < 1 || window > 100) p.push_back("window must be in [1, 100]");
    return p;
}

void KeyframeAccumulator::add(StampedSweep sweep) {
    sweeps_.push_back(std::move(sweep));
    while (static_cast<int>(sweeps_.size()) > params_.window) sweeps_.pop_front();
}

PointCloud deskew_sweep(const StampedSweep& s, const Isometry3& T_target_world, bool deskew) {
    PointCloud c = s.points_sensor;
    const bool moved = !s.T_world_sensor_start.isApprox(s.T_world_sensor_end, 1e-12);
    const bool per_point = deskew && moved && c.time_s.size() == c.size() && s.duration_s > 0.0;
    const Isometry3 T_target_start = T_target_world * s.T_world_sensor_start;
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (per_point) {
            const double alpha = std::clamp(c.time_s[i] / s.duration_s, 0.0, 1.0);
            const Isometry3 T_target_point = T_target_world * interpolate(s.T_world_sensor_start, s.T_world_sensor_end, alpha);
            c.xyz[i] = (T_target_point * c.xyz[i].cast<double>()).cast<float>();
        } else {
            c.xyz[i] = (T_target_start * c.xyz[i].cast<double>()).cast<float>();
        }
    }
    return c;
}

PointCloud KeyframeAccumulator::keyframe(Isometry3* T_world_keyframe) const {
    PointCloud out;
    if (sweeps_.empty()) return out;
    const StampedSweep& newest = sweeps_.back();
    const Isometry3 T_keyframe_world = newest.T_world_sensor_start.inverse();
    if (T_world_keyframe) *T_world_keyframe = newest.T_world_sensor_start;
    for (const StampedSweep& s : sweeps_) {
        PointCloud c = deskew_sweep(s, T_keyframe_world, params_.deskew);
        for (float& t : c.time_s) t = static_cast<float>(t + s.stamp_s - newest.stamp_s);
        out.append(c);
    }
    return out;
}

}  // namespace makeway::perception
