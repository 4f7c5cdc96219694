#pragma once
// One closed-loop navigation run of a named method with what it needs: no objects (con, oppo), the
// ground truth (gt-perc) or the online pipeline on wheel odometry (ours: keyframes, ground plane,
// detector, verification against the CAD models of the scene's furniture, object map).
#include <memory>
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

/// The method plans with learned zones (when given: `--zones`, or a building's own sessions);
/// risk time stays scored on the zones the configuration draws by hand, the same for every method.
void plan_with_zones(eval::NavParams& params,
                     const std::shared_ptr<const costmap::LearnedZones>& zones);

}  // namespace makeway::apps
