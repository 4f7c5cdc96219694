#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "makeway/eval/detection_eval.hpp"
#include "makeway/eval/keyframe_stages.hpp"
#include "makeway/pipeline/pipeline.hpp"

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

// The general weights (issue 32: real models, clutter and four sensors in training, the input
// levelled by the keyframe's ground plane), committed beside the default ones.
perception::Detector general_detector() {
    const fs::path weights = fs::path(MAKEWAY_SOURCE_DIR) / "models" / "detector_general.pt";
    EXPECT_TRUE(fs::exists(weights)) << "the general weights are committed: " << weights;
    return perception::Detector::load(weights);
}

// Issue 32: things of furniture size that are not furniture (crates, cabinets, bins, sofas,
// shelves, plants, standing people, lamps, boxes), in rooms that hold nothing else, seeds never
// trained on. The general weights, trained with clutter as negatives, still fire now and then
// (issue 32's target, none, is not met): here 7 false detections in 20 keyframes, six of them on
// potted plants (the default weights: 1.99 per keyframe on eval-detection's clutter set). The
// object map, which needs several detections of a thing, ends both drives empty: a plant it held
// for a keyframe on the way is gone again. Each detection is printed with what it lay on.
TEST(DetectionEval, RoomsOfClutterAloneGiveFewFalseDetectionsAndAnEmptyMap) {
    const perception::Detector detector = general_detector();
    DatasetParams p;
    p.scenes = 2;
    p.seed = 3000000;
    p.max_keyframes_per_scene = 10;
    p.keyframe_every = 5;
    p.clutter.count = 8;
    p.clutter_only = true;
    std::vector<sim::Scene> scenes;
    const std::vector<LabelledKeyframe> kfs = generate_detection_dataset(p, {}, &scenes);
    ASSERT_EQ(kfs.size(), 20u);
    std::size_t items = 0;
    for (const sim::Scene& s : scenes) items += s.environment.size();
    EXPECT_GE(items, 12u);
    // What a detection in keyframe k lies on.
    const auto what = [&](std::size_t k, const OrientedBox& box_sensor) {
        const Eigen::Vector3d w = kfs[k].T_world_sensor * box_sensor.centre_m;
        std::string near;
        for (const sim::EnvironmentMesh& e : scenes[kfs[k].sequence].environment) {
            Eigen::Vector3d lo, hi;
            mesh_bounds(*e.mesh_world, lo, hi);
            if ((0.5 * (lo + hi) - w).head<2>().norm() < 1.0) near += " " + e.mesh_file;
        }
        return "keyframe " + std::to_string(k) + ", near" + near;
    };
    std::vector<std::vector<Detection>> found;
    std::size_t detections = 0;
    for (std::size_t k = 0; k < kfs.size(); ++k) {
        found.push_back(detector.detect(kfs[k].cloud_sensor, kfs[k].ground_plane_sensor));
        detections += found.back().size();
        for (const Detection& d : found.back())
            std::cout << "false " << to_string(d.cls) << " " << d.score << ": "
                      << what(k, d.box_sensor) << "\n";
    }
    EXPECT_LE(detections, 8u) << "at most 0.4 false detections per keyframe";
    const auto map = track_keyframes(
        kfs, found,
        pipeline::tracker_params_for(&detector, pipeline::SystemParams{}.tracker, false),
        p.range_m);
    std::size_t mapped = 0;  // in each drive's last keyframe: what the robot is left with
    for (std::size_t k = 0; k < map.size(); ++k) {
        if (k + 1 < map.size() && kfs[k + 1].sequence == kfs[k].sequence) continue;
        mapped += map[k].size();
        for (const Detection& d : map[k])
            std::cout << "mapped " << to_string(d.cls) << ": " << what(k, d.box_sensor) << "\n";
    }
    EXPECT_EQ(mapped, 0u);
}

// Issue 32: the same room seen by a 16-beam VLP-16 at the training's height and by a 128-beam
// OS1-128 mounted twice as high: the input is levelled by each keyframe's ground plane, and both
// find the room's chairs.
TEST(DetectionEval, SixteenAndOneHundredTwentyEightBeamsBothFindTheChairs) {
    const perception::Detector detector = general_detector();
    ASSERT_GT(detector.params().level_height_m, 0.0) << "the general weights level their input";
    for (const auto& [pattern, height] :
         {std::pair{sim::BeamPattern::kVlp16, 0.45}, std::pair{sim::BeamPattern::kOs1_128, 0.9}}) {
        DatasetParams p;
        p.scenes = 1;
        p.seed = 3000100;
        p.max_keyframes_per_scene = 6;
        p.keyframe_every = 5;
        p.beam_pattern = pattern;
        p.sensor_height_m = height;
        p.exclude_styles = {"armchair", "round_table"};
        const std::vector<LabelledKeyframe> kfs = generate_detection_dataset(p);
        ASSERT_EQ(kfs.size(), 6u);
        std::vector<std::vector<Detection>> found;
        std::vector<std::vector<LabelledBox>> gt;
        for (const LabelledKeyframe& kf : kfs) {
            found.push_back(detector.detect(kf.cloud_sensor, kf.ground_plane_sensor));
            gt.push_back(ground_truth_of(kf));
        }
        const DetectionMetrics m = evaluate_detections(found, gt);
        const ClassDetectionMetrics& chairs = m.per_class.at(ObjectClass::kChair);
        EXPECT_GT(chairs.ground_truth, 20u);
        EXPECT_GT(chairs.ap_25, 0.8) << sim::to_string(pattern) << " at " << height << " m";
    }
}

}  // namespace
}  // namespace makeway::eval
