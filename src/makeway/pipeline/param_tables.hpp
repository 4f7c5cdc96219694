#pragma once
// The online system's own configurable parameters (common/param_table.hpp); each stage's table
// lives with its stage, these are the pipeline's: keyframes, tracked shapes, the navigator's
// policy.
#include "makeway/common/param_table.hpp"
#include "makeway/pipeline/system_params.hpp"
#include "makeway/pipeline/tracked_shapes.hpp"

namespace makeway::pipeline {

/// Keyframes with the ground plane (`ground_` keys) and the ground and ceiling filter.
const ParamTable<KeyframeParams>& keyframe_table();
const ParamTable<TrackedShapeParams>& tracked_shape_table();
/// The navigator's policy around A* and DWA (replanning, recoveries, tolerances).
const ParamTable<NavigatorParams>& navigator_policy_table();

}  // namespace makeway::pipeline
