#pragma once
// The collision monitor remembers returns near the robot that the sensor can no longer see, and
// forgets them once it could see their place again; where that is depends on the LiDAR's lowest
// beam (CollisionMonitorParams::lowest_beam_deg). Told a lower beam than the sensor has (a
// VLP-32C's -25 deg on a VLP-16, which sees 15 deg down), it forgets the chair legs it closes in
// on: in the simulator's benchmark that made 2 robot-caused contacts in 25 scenes. A sweep shows
// its lowest beam (the floor returns' elevation), so the robot checks the setting against its first
// sweep.
#include <optional>
#include <string>

#include "makeway/common/point_cloud.hpp"
#include "makeway/planning/collision_monitor.hpp"

namespace makeway::planning {

/// The elevation of the sweep's lowest beam [deg] in the sensor frame: a low percentile (0.2 %) of
/// its returns' elevations, so that a few stray returns do not count; nullopt for fewer than 500
/// finite returns beyond 0.3 m.
std::optional<double> lowest_beam_seen_deg(const PointCloud& sweep_sensor);

/// Raises `monitor.lowest_beam_deg` to the beam the sweep shows when that is more than 0.5 deg
/// higher (never lowers it: a lower setting only makes the monitor forget sooner), and says so in
/// one line naming the key; empty when nothing changed.
std::string raise_lowest_beam(CollisionMonitorParams& monitor, const PointCloud& sweep_sensor);

}  // namespace makeway::planning
