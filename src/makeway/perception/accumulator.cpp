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

PointCloud KeyframeAccumulator::keyframe(Isometry3* T_world_keyframe) const {
    PointCloud out;
    if (sweeps_.empty()) return out;
    const StampedSweep& newest = sweeps_.back();
    const Isometry3 T_keyframe_world = newest.T_world_sensor_start.inverse();
    if (T_world_keyframe) *T_world_keyframe = newest.T_world_sensor_start;
    for (const StampedSweep& s : sweeps_) {
        PointCloud c = s.points_sensor;
        const bool have_time = !c.time_s.empty();
        const bool deskew = params_.deskew && have_time && !s.T_world_sensor_start.isApprox(s.T_world_sensor_end, 1e-12);
        const Isometry3 T_kf_start = T_keyframe_world * s.T_world_sensor_start;
        for (std::size_t i = 0; i < c.size(); ++i) {
            if (deskew) {
                const double alpha = std::clamp(c.time_s[i] / s.duration_s, 0.0, 1.0);
                const Isometry3 T_kf_point = T_keyframe_world * interpolate(s.T_world_sensor_start, s.T_world_sensor_end, alpha);
                c.xyz[i] = (T_kf_point * c.xyz[i].cast<double>()).cast<float>();
            } else {
                c.xyz[i] = (T_kf_start * c.xyz[i].cast<double>()).cast<float>();
            }
            if (have_time) c.time_s[i] = static_cast<float>(c.time_s[i] + s.stamp_s - newest.stamp_s);
        }
        out.append(c);
    }
    return out;
}

}  // namespace makeway::perception
