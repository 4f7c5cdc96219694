#pragma once
// The KITTI tracking protocol as AB3DMOT reports it (Weng et al., IROS 2020, its evaluation of
// the KITTI devkit with 3D IoU): one class at a time; DontCare regions and neighbouring classes
// (Van for Car, Person_sitting for Pedestrian) ignored; truncated or heavily occluded ground truth
// ignored; a track's score is its mean over the sequence; CLEAR MOT at each score threshold that
// reaches the next of 40 recall steps, averaged into sAMOTA, AMOTA and AMOTP.
//
// Re-implemented from the published description and the devkit's documented rules; the remaining
// differences (README "KITTI protocol") are: tracker boxes without a 2D box (-1) are never ignored
// by height or DontCare overlap (the devkit ignores every such box, so their false positives
// vanish); only unmatched tracker boxes can be ignored (as the devkit's first pass; its later
// passes remember matches of earlier thresholds); the optional camera field of view is a
// horizontal angle around the sensor's x axis, not an image-plane test.
#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "makeway/common/oriented_box.hpp"

namespace makeway::eval {

struct KittiBox {
    int track_id = -1;
    std::string type;                               ///< lower case: "car", "van", "dontcare", ...
    int truncation = 0, occlusion = 0;              ///< KITTI tracking levels (0, 1, 2)
    std::array<double, 4> bbox_px{-1, -1, -1, -1};  ///< x1 y1 x2 y2; -1: none
    OrientedBox box;                                ///< makeway frame (x forward, y left, z up)
    double score = 0.0;
    bool has_bbox() const {
        return bbox_px[2] > bbox_px[0] && bbox_px[3] > bbox_px[1] && bbox_px[0] >= 0;
    }
};
using KittiFrame = std::vector<KittiBox>;
using KittiSequence = std::vector<KittiFrame>;  ///< frame k at index k

struct KittiEvalParams {
    std::string cls = "car";        ///< the class evaluated (lower case)
    double min_iou_3d = 0.25;       ///< a match needs at least this 3D IoU
    int max_truncation = 0;         ///< ground truth more truncated is ignored
    int max_occlusion = 2;          ///< ground truth more occluded is ignored
    double min_height_px = 25.0;    ///< unmatched tracker boxes no taller (2D) are ignored
    bool ignore_neighbours = true;  ///< Van for Car, Person_sitting for Pedestrian
    bool use_dont_care =
        true;  ///< unmatched tracker boxes mostly inside a DontCare box are ignored
    double fov_deg =
        0.0;  ///< > 0: only boxes whose centre lies within +-fov/2 of the sensor's x axis
    int recall_steps = 40;  ///< sAMOTA / AMOTA / AMOTP average over this many recall steps
    /// Reproduce the score handling of AB3DMOT's evaluate.py to the last bit: it overwrites every
    /// box's score with its track's mean and, at each later threshold, averages those means again
    /// (sum of n equal values over n, in floating point), so a track whose re-averaged score lands
    /// an ulp under a threshold equal to its own first mean is dropped there; its best-MOTA row is
    /// one more such pass. Off: each threshold compares the track's one mean (clean arithmetic).
    bool devkit_rounding = false;
};

/// CLEAR MOT at one score threshold, with the devkit's counting: tp includes ignored true
/// positives, fn and fp exclude ignored ones, gt = ground truth less the ignored.
struct KittiClear {
    double threshold = 0.0, recall_target = 1.0;
    double mota = 0.0, motp = 0.0, moda = 0.0, smota = 0.0;
    double recall = 0.0, precision = 0.0, f1 = 0.0;
    double mostly_tracked = 0.0, partly_tracked = 0.0,
           mostly_lost = 0.0;  ///< fractions of trajectories
    std::size_t tp = 0, fp = 0, fn = 0, ignored_tp = 0, ignored_fn = 0, ignored_tracker = 0;
    std::size_t id_switches = 0, fragmentations = 0, gt = 0, frames = 0;
};

struct KittiEvalResult {
    KittiClear all;                 ///< every track box (no threshold)
    KittiClear best;                ///< at the threshold of best MOTA
    std::vector<KittiClear> curve;  ///< one per recall step reached
    double samota = 0.0, amota = 0.0, amotp = 0.0;
    std::size_t gt_boxes = 0, tracker_boxes = 0;  ///< of the class, before any ignoring
};

/// Score thresholds at which recall reaches 1/steps, 2/steps, ... (the devkit's rule on the
/// scores of the matched track boxes); the first (zero recall) is dropped as the devkit does.
std::vector<std::pair<double, double>> kitti_thresholds(std::vector<double> tp_scores,
                                                        std::size_t num_gt, int recall_steps);

/// `gt` and `tracks` hold the same sequences in the same order (frames may differ in count).
/// `track_scores` (per sequence, track id -> score): the tracks' scores to use instead of their
/// means.
KittiClear evaluate_kitti_at(
    const std::vector<KittiSequence>& gt, const std::vector<KittiSequence>& tracks,
    const KittiEvalParams& params, double threshold, double recall_target = 1.0,
    std::vector<double>* tp_scores = nullptr,
    const std::vector<std::unordered_map<int, double>>* track_scores = nullptr);
KittiEvalResult evaluate_kitti(const std::vector<KittiSequence>& gt,
                               const std::vector<KittiSequence>& tracks,
                               const KittiEvalParams& params);

}  // namespace makeway::eval
