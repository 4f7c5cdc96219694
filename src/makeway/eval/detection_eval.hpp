#pragma once
// The detector's evaluation (issue: held-out simulated scenes): seeds never used for training and,
// separately, scenes whose chairs and tables are all of styles left out of training. The paper's
// ablation stages: the network alone; + geometric verification against CAD models; + tracking (the
// object map built from the verified detections, scored in every keyframe against the objects in
// range that the drive has seen so far).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "makeway/eval/detection_dataset.hpp"
#include "makeway/eval/detection_metrics.hpp"
#include "makeway/eval/keyframe_stages.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace makeway::eval {

/// Where verification's CAD models come from.
enum class CadSource {
    kScene,    ///< the models of the scene's own furniture (the paper's setting)
    kDefault,  ///< one model per style at default dimensions (furniture whose models are unknown)
    kNone,     ///< no CAD models at all (with a shape prior: the learned shapes alone)
};

struct DetectionEvalParams {
    int scenes = 6;
    std::uint64_t seed = 1000000;  ///< held out: training seeds stay below this
    std::vector<std::string> left_out_styles{"armchair", "round_table"};
    /// Keyframes every 5 sweeps (2 Hz), the full system's cadence, which the tracking stage needs.
    int keyframe_every = 5;
    int max_keyframes_per_scene = 60;
    CadSource cad = CadSource::kScene;
    CadFit cad_fit = CadFit::kExact;  ///< with kScene: the scene's own models or approximations
    /// Learned shapes for detections no CAD model fits (null: none). Must outlive the run.
    const verification::ShapePrior* shape_prior = nullptr;
    pipeline::SystemParams system;  ///< the online system's front end, verification and tracker
    int latency_keyframes = 20;     ///< timed on 1 and 2 threads
    /// Real furniture models never trained on (split_furniture's held_out): a third set of
    /// scenes whose every chair and table is one of them, verified against those same models.
    /// Empty: no such set.
    std::vector<UserFurniture> real_held_out;
    /// A fourth set: the same kind of rooms with the furniture taken out and clutter put in
    /// (sim/clutter.hpp), where everything the network reports is a false positive. count 0: no
    /// such set.
    sim::ClutterParams clutter{.count = 8};
    /// The sensor of every set's drives: its beams and height above the floor.
    sim::BeamPattern beam_pattern = sim::BeamPattern::kVlp32c;
    double sensor_height_m = 0.45;
};

/// The ablation on one set of scenes.
struct StageMetrics {
    DetectionMetrics network, verified, tracked;
    std::size_t keyframes = 0;
};

/// False positives on rooms of clutter alone, per keyframe: the network's detections (all above
/// its decoding threshold, the operating point) and the objects the map holds (no CAD models, as
/// the pipeline maps the network's boxes then).
struct ClutterMetrics {
    std::size_t keyframes = 0, clutter_items = 0, network = 0, tracked = 0;
    std::vector<double> network_scores;  ///< every false detection's score, for other thresholds
    double network_per_keyframe() const { return keyframes ? double(network) / keyframes : 0.0; }
    double tracked_per_keyframe() const { return keyframes ? double(tracked) / keyframes : 0.0; }
};

struct DetectionEvalResult {
    StageMetrics held_out;                      ///< held-out seeds, styles seen in training
    StageMetrics left_out;                      ///< scenes of left-out styles only
    std::optional<StageMetrics> real_held_out;  ///< real models never trained on (if given)
    std::optional<ClutterMetrics> clutter;      ///< rooms of clutter alone (if asked for)
    double latency_ms_median_1t = 0, latency_ms_p99_1t = 0, latency_ms_median_2t = 0,
           latency_ms_p99_2t = 0;
};

DetectionEvalResult run_detection_eval(
    const perception::Detector& detector, const DetectionEvalParams& params,
    const std::function<void(const std::string&, int, int)>& progress = {});

}  // namespace makeway::eval
