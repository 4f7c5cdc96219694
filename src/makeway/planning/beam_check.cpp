#include "makeway/planning/beam_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "makeway/common/angles.hpp"

namespace makeway::planning {

std::optional<double> lowest_beam_seen_deg(const PointCloud& sweep_sensor) {
    std::vector<double> elevations;
    elevations.reserve(sweep_sensor.size());
    for (const Eigen::Vector3f& p : sweep_sensor.xyz) {
        const double r = std::hypot(p.x(), p.y());
        if (!p.allFinite() || std::hypot(r, p.z()) < 0.3) continue;
        elevations.push_back(rad_to_deg(std::atan2(p.z(), r)));
    }
    if (elevations.size() < 500) return std::nullopt;
    const auto k = elevations.begin() + static_cast<std::ptrdiff_t>(elevations.size() / 500);
    std::nth_element(elevations.begin(), k, elevations.end());
    return *k;
}

std::string raise_lowest_beam(CollisionMonitorParams& monitor, const PointCloud& sweep_sensor) {
    const std::optional<double> seen = lowest_beam_seen_deg(sweep_sensor);
    if (!seen || *seen <= monitor.lowest_beam_deg + 0.5) return "";
    char line[256];
    std::snprintf(line, sizeof(line),
                  "collision_monitor.lowest_beam_deg is %.1f but the sensor's lowest beam is at "
                  "%.1f deg (first sweep): using %.1f (set it for this sensor)",
                  monitor.lowest_beam_deg, *seen, *seen);
    monitor.lowest_beam_deg = *seen;
    return line;
}

}  // namespace makeway::planning
