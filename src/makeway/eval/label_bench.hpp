#pragma once
// `makeway bench label`: the automatic annotation against the simulator's truth. Each scene is
// driven in several sessions (the furniture moved between them as people leave it, walkers and
// pulled chairs within them); the labeller gets the sweeps and wheel odometry alone, the truth of
// the same sweeps scores it:
// - point classes: IoU per class (Ground, Permanent, Movable, Dynamic) on every keyframe's newest
//   sweep (truth: chairs and tables Movable, people Dynamic, ground Ground, the rest Permanent);
// - instance segmentation: panoptic quality (Kirillov et al. 2019) over the chair and table
//   instances of those sweeps (a match is IoU > 0.5; segments under 10 points are not counted);
// - boxes: AP at 3D IoU 0.25 / 0.5 of each keyframe's auto-labelled objects against the truth
//   boxes of the objects seen as the labeller's keyframes see them (min_points over the keyframe's
//   window of sweeps, ground excluded), and yaw within 10 deg of the matched boxes.
// The scene's chair pushers pull some chairs to and fro during a session: a static label cannot
// hold them. Every measure is reported with them as chairs (the class truth) and again by motion
// (Thomas et al.'s definitions: what moves within a session is Dynamic; its boxes neither truth nor
// false labels).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "makeway/eval/detection_metrics.hpp"
#include "makeway/labelling/labeller.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {

struct LabelBenchParams {
    int scenes = 10;
    int sessions = 3;
    std::uint64_t seed = 0;
    int max_sweeps = 600;  ///< per session (60 s at 10 Hz), fewer when the drive ends
    bool cad = true;       ///< the scene's CAD models (else every object keeps its PCA box)
    std::size_t truth_min_points =
        10;  ///< panoptic segments with fewer points in a sweep are not counted
    labelling::LabelParams label;
    sim::OdometryNoiseParams odometry;
};

struct PanopticQuality {
    std::size_t tp = 0, fp = 0, fn = 0;
    double iou_sum = 0.0;
    double pq() const {
        const double d = tp + 0.5 * (fp + fn);
        return d > 0 ? iou_sum / d : 0.0;
    }
    double sq() const { return tp ? iou_sum / static_cast<double>(tp) : 0.0; }
    double rq() const {
        const double d = tp + 0.5 * (fp + fn);
        return d > 0 ? tp / d : 0.0;
    }
};

struct LabelBenchScene {
    std::string name;
    std::vector<double> alignment_residual_m,
        alignment_correction_m;  ///< per session after the first
    std::array<std::array<std::size_t, labelling::kNumPointClasses>, labelling::kNumPointClasses>
        confusion{};  ///< [truth][predicted]
    std::array<std::array<std::size_t, labelling::kNumPointClasses>, labelling::kNumPointClasses>
        confusion_by_motion{};
    PanopticQuality panoptic;
    DetectionMetrics boxes, still_boxes;
    std::size_t objects = 0, cad_objects = 0, unknown_objects = 0, keyframes = 0, sweeps = 0;
    double label_seconds = 0.0;  ///< the labeller alone (front end included), not the simulation
};

struct LabelBenchResult {
    std::vector<LabelBenchScene> scenes;
    std::array<std::array<std::size_t, labelling::kNumPointClasses>, labelling::kNumPointClasses>
        confusion{}, confusion_by_motion{};
    std::array<double, labelling::kNumPointClasses> iou{}, iou_by_motion{};
    PanopticQuality panoptic;
    DetectionMetrics boxes;        ///< over every keyframe of every scene
    DetectionMetrics still_boxes;  ///< the same without the chairs pulled during their session
};

/// IoU per class of a confusion matrix [truth][predicted].
std::array<double, labelling::kNumPointClasses> class_iou(
    const std::array<std::array<std::size_t, labelling::kNumPointClasses>,
                     labelling::kNumPointClasses>& confusion);

/// Panoptic matching of one frame: truth and predicted instance ids per point (0: none).
void add_panoptic(const std::vector<std::uint32_t>& truth,
                  const std::vector<std::uint32_t>& predicted, std::size_t min_points,
                  PanopticQuality& pq);

/// Called for every simulated sweep: the session, its scene, the frame (truth included), and
/// `feed`, which hands the frame to the labeller as a robot records it and returns the front end's
/// result.
using SessionFrameHook =
    std::function<void(int session, const sim::Scene& scene, sim::SimFrame& frame,
                       const std::function<pipeline::FrontEndResult(sim::SimFrame&)>& feed)>;

/// Drives `base` in `sessions` sessions (sim::make_session: furniture moved between them) along
/// each session's auto route, up to max_sweeps each, into the labeller (begin_session per session).
/// Throws std::runtime_error when a session has no route.
void drive_sessions(labelling::Labeller& labeller, const sim::Scene& base, int sessions,
                    int max_sweeps, std::uint64_t seed, const sim::OdometryNoiseParams& odometry,
                    const SessionFrameHook& on_frame = {});

LabelBenchResult run_label_bench(const LabelBenchParams& params,
                                 const std::function<void(int, int)>& progress = {});

}  // namespace makeway::eval
