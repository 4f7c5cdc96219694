#pragma once
// The planners' and the collision monitor's configurable parameters (common/param_table.hpp); the
// robot's footprint, speeds and accelerations come from the robot description, not from here.
#include "makeway/common/param_table.hpp"
#include "makeway/planning/astar.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/planning/dwa.hpp"

namespace makeway::planning {

const ParamTable<AStarParams>& astar_table();
const ParamTable<DwaParams>& dwa_table();
const ParamTable<CollisionMonitorParams>& collision_monitor_table();

}  // namespace makeway::planning
