#pragma once
// 3D detection metrics per class, following the ScanNet / SUN RGB-D protocol used by CAGroup3D:
// detections sorted by score are matched greedily to unmatched ground truth at a 3D IoU
// threshold; AP is the area under the precision envelope (all points), AR the recall with every
// detection. Orientation accuracy is over true positives at the lower threshold.
#include <map>
#include <vector>

#include "makeway/common/detection.hpp"

namespace makeway::eval {

struct LabelledBox {
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box;
    bool yaw_scored = true;     ///< false for rotationally symmetric objects (round tables, stools)
    bool pi_symmetric = false;  ///< rectangular tables: yaw scored modulo pi
};

struct ClassDetectionMetrics {
    double ap_25 = 0.0, ap_50 = 0.0, ar_25 = 0.0, ar_50 = 0.0;
    double yaw_within_10deg = 0.0,
           yaw_within_30deg = 0.0;  ///< of yaw-scored true positives at IoU 0.25
    std::size_t ground_truth = 0, detections = 0;
};

struct DetectionMetrics {
    std::map<ObjectClass, ClassDetectionMetrics> per_class;
    double map_25 = 0.0, map_50 = 0.0, mar_25 = 0.0,
           mar_50 = 0.0;  ///< means over classes with ground truth
};

/// frames[k]: the detections and ground truth of keyframe k, in one frame (any).
DetectionMetrics evaluate_detections(const std::vector<std::vector<Detection>>& detections,
                                     const std::vector<std::vector<LabelledBox>>& ground_truth);

/// Average precision of one ranked list: `hit[i]` whether the i-th best detection is a true
/// positive, out of `positives` ground-truth boxes (all-point interpolation).
double average_precision(const std::vector<bool>& hit, std::size_t positives);

}  // namespace makeway::eval
