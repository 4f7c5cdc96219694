#pragma once
// The detector's evaluation (issue: held-out simulated scenes): seeds never used for training and,
// separately, scenes whose chairs and tables are all of styles left out of training. Stages: the
// network alone, then with geometric verification against a CAD library of every style.
#include <functional>
#include <string>
#include <vector>

#include "makeway/eval/detection_dataset.hpp"
#include "makeway/eval/detection_metrics.hpp"
#include "makeway/perception/detector.hpp"

namespace makeway::eval {

struct DetectionEvalParams {
    int scenes = 6;
    std::uint64_t seed = 1000000;            ///< held out: training seeds stay below this
    std::vector<std::string> left_out_styles{"armchair", "round_table"};
    bool verification = true;
    int latency_keyframes = 20;              ///< timed on 1 and 2 threads
};

struct DetectionEvalResult {
    DetectionMetrics network, verified;                  ///< held-out seeds, styles seen in training
    DetectionMetrics left_out_network, left_out_verified;  ///< scenes of left-out styles only
    double latency_ms_median_1t = 0, latency_ms_p99_1t = 0, latency_ms_median_2t = 0, latency_ms_p99_2t = 0;
    std::size_t keyframes = 0, left_out_keyframes = 0;
};

DetectionEvalResult run_detection_eval(const perception::Detector& detector, const DetectionEvalParams& params,
                                       const std::function<void(const std::string&, int, int)>& progress = {});

/// Ground truth of a keyframe for the metrics (round tables and stools: yaw not scored).
std::vector<LabelledBox> ground_truth_of(const LabelledKeyframe& keyframe);

}  // namespace makeway::eval
