#pragma once
// Multi-object tracking metrics on 3D boxes, following the published definitions: CLEAR MOT
// (Bernardin and Stiefelhagen 2008; matches kept from the previous frame while their IoU holds, the
// rest by the Hungarian algorithm) and HOTA with DetA and AssA (Luiten et al., IJCV 2021; alpha
// from 0.05 to 0.95, Hungarian on the global-alignment-weighted similarity per frame). Similarity:
// 3D IoU.
#include <cstdint>
#include <map>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway::eval {

struct TrackedBox {
    std::uint32_t id = 0;
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box;
};
using TrackingFrame = std::vector<TrackedBox>;

struct ClearMot {
    double mota = 0.0, motp = 0.0;  ///< MOTP: mean IoU of the matches
    std::size_t gt = 0, tp = 0, fp = 0, fn = 0, id_switches = 0, fragmentations = 0;
};

struct Hota {
    double hota = 0.0, deta = 0.0, assa = 0.0;  ///< means over the 19 alphas
};

struct TrackingMetrics {
    ClearMot clear;
    Hota hota;
};

struct TrackingMetricsParams {
    double clear_iou_threshold = 0.25;  ///< CLEAR MOT match threshold
};

/// Metrics over a sequence (gt[k] and tracks[k] are frame k); every box counts, whatever its class.
TrackingMetrics evaluate_tracking(const std::vector<TrackingFrame>& gt,
                                  const std::vector<TrackingFrame>& tracks,
                                  const TrackingMetricsParams& params = {});

/// The same per class: each class's ground truth against the tracks labelled with that class.
std::map<ObjectClass, TrackingMetrics> evaluate_tracking_per_class(
    const std::vector<TrackingFrame>& gt, const std::vector<TrackingFrame>& tracks,
    const TrackingMetricsParams& params = {});

}  // namespace makeway::eval
