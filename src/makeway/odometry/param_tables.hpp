#pragma once
// The LiDAR odometry's configurable parameters (common/param_table.hpp).
#include "makeway/common/param_table.hpp"
#include "makeway/odometry/lidar_odometry.hpp"

namespace makeway::odometry {

const ParamTable<OdometryParams>& odometry_table();

}  // namespace makeway::odometry
