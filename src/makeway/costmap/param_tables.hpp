#pragma once
// The costmap layers' configurable parameters (common/param_table.hpp).
#include "makeway/common/param_table.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/obstacle_layer.hpp"

namespace makeway::costmap {

/// The zones' shapes and cost profiles (nested: `chair.side_m`).
const ParamTable<AffordanceParams>& affordance_table();
/// The numbers of a zones file (learned_zone.hpp), not its motions.
const ParamTable<LearnedZones>& learned_zones_table();
/// The obstacle layer's marking and clearing (the body comes from the robot).
const ParamTable<ObstacleLayerParams>& obstacle_layer_table();
/// The inflation layer's decay (the radii come from the robot and the method).
const ParamTable<InflationParams>& inflation_table();

}  // namespace makeway::costmap
