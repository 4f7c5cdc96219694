#pragma once
// The front end's configurable parameters (common/param_table.hpp).
#include "makeway/common/param_table.hpp"
#include "makeway/perception/ground.hpp"

namespace makeway::perception {

const ParamTable<GroundPlaneParams>& ground_plane_table();
const ParamTable<GroundFilterParams>& ground_filter_table();

}  // namespace makeway::perception
