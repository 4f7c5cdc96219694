#pragma once
// The navigation benchmark's parameters from a configuration: the simulated robot, LiDAR and
// odometry noise, and the online system exactly as `makeway run` and makeway_node build it
// (online_system_params). Its own library: io never links the evaluation otherwise.
#include "io/sim_config.hpp"
#include "makeway/eval/navigation.hpp"

namespace makeway::io {

/// NavParams from the configuration's lidar, robot, odometry, simulation and online-system
/// sections.
eval::NavParams nav_params(const SimConfig& config);

}  // namespace makeway::io
