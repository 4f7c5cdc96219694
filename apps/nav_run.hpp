#pragma once
// One closed-loop navigation run of a named method with what it needs: no objects (con, oppo), the
// ground truth (gt-perc) or the online pipeline on wheel odometry (ours: keyframes, ground plane,
// detector, verification against the CAD models of the scene's furniture, object map).
#include <string>

#include "makeway/eval/navigation.hpp"
#include "makeway/perception/detector.hpp"

namespace makeway::apps {

/// `detector` is needed by `ours` only (std::invalid_argument without it). With `shapes`, `ours`
/// verifies against the learned shapes instead of the scene's CAD models (furniture without
/// models).
eval::NavRunResult run_nav_method(const sim::Scene& scene, const std::string& method,
                                  const eval::NavParams& params,
                                  const perception::Detector* detector,
                                  const verification::ShapePrior* shapes = nullptr);

}  // namespace makeway::apps
