#pragma once
// The simulator's configurable parameters (common/param_table.hpp): the scene generator, the
// LiDAR and the wheel odometry's drift.
#include "makeway/common/param_table.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::sim {

const ParamTable<SceneGenParams>& scene_gen_table();
const ParamTable<LidarParams>& lidar_table();
const ParamTable<OdometryNoiseParams>& wheel_noise_table();

}  // namespace makeway::sim
