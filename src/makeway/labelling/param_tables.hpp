#pragma once
// The automatic annotation's configurable parameters (common/param_table.hpp): the `labelling`
// section (its front end is the online system's sections).
#include "makeway/common/param_table.hpp"
#include "makeway/labelling/labeller.hpp"
#include "makeway/labelling/occupancy.hpp"

namespace makeway::labelling {

const ParamTable<OccupancyParams>& occupancy_table();
/// The labeller's own keys with the occupancy grid's, the clustering's (`dbscan_`) and the CAD
/// alignment's acceptance (`verify_e_max_m`).
const ParamTable<LabelParams>& label_table();

}  // namespace makeway::labelling
