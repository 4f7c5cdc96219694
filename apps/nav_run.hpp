#pragma once
// One closed-loop navigation run of a named method with what it needs: no objects (con, oppo), the
// ground truth (gt-perc) or the online pipeline on wheel odometry (ours: keyframes, ground plane,
// detector, verification against the CAD models of the scene's furniture, object map).
#include <string>

#include "makeway/eval/navigation.hpp"
#include "makeway/perception/detector.hpp"

namespace makeway::apps {

/// `detector` is needed by `ours` only (std::invalid_argument without it).
eval::NavRunResult run_nav_method(const sim::Scene& scene, const std::string& method, const eval::NavParams& params,
                                  const perception::Detector* detector);

}  // namespace makeway::apps
