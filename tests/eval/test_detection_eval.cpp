#include <gtest/gtest.h>

#include <filesystem>

#include "makeway/eval/detection_eval.hpp"

namespace makeway::eval {
namespace {

namespace fs = std::filesystem;

// Without CAD models (and no learned shapes) the online system maps the network's boxes with its
// scores as the evidence (Pipeline::perceive). The evaluation's stages say the same: the verified
// stage is the network's, and the tracked stage is the map built from it (an empty library that
// rejected every detection scored both 0 before, whatever the network found).
TEST(DetectionEval, WithoutCadModelsTheStagesKeepTheNetworksBoxes) {
    const fs::path weights = fs::path(MAKEWAY_SOURCE_DIR) / "models" / "detector.pt";
    ASSERT_TRUE(fs::exists(weights)) << "the default weights are committed: " << weights;
    const perception::Detector detector = perception::Detector::load(weights);
    DetectionEvalParams p;
    p.scenes = 1;
    p.max_keyframes_per_scene = 8;
    p.latency_keyframes = 1;
    p.cad = CadSource::kNone;
    p.clutter.count = 0;  // no false-positive set
    const DetectionEvalResult r = run_detection_eval(detector, p);
    const StageMetrics& s = r.held_out;
    ASSERT_GT(s.keyframes, 0u);
    EXPECT_GT(s.network.map_25, 0.8);  // a trained network on seeds it never saw
    EXPECT_EQ(s.verified.map_25, s.network.map_25);
    EXPECT_EQ(s.verified.map_50, s.network.map_50);
    for (const auto& [cls, m] : s.network.per_class)
        EXPECT_EQ(s.verified.per_class.at(cls).detections, m.detections);
    EXPECT_GT(s.tracked.map_25, 0.5);
}

}  // namespace
}  // namespace makeway::eval
