#pragma once
// The robot description's configurable parameters (common/param_table.hpp): the `robot` section.
#include "makeway/common/param_table.hpp"
#include "makeway/common/robot_description.hpp"

namespace makeway {

const ParamTable<RobotDescription>& robot_description_table();

}  // namespace makeway
