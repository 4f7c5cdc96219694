#pragma once
// The object map's configurable parameters (common/param_table.hpp).
#include "makeway/common/param_table.hpp"
#include "makeway/tracking/box_kalman_filter.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::tracking {

/// The map's association, lifecycle and fusion, each class's motion prior (`chair_` keys) and
/// the box filter's noise.
const ParamTable<TrackerParams>& tracker_table();
const ParamTable<KalmanParams>& kalman_table();
const ParamTable<MotionPrior>& motion_prior_table();

}  // namespace makeway::tracking
