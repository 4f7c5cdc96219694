#pragma once
// Non-maximum suppression of rotated boxes: the detector's last step.
#include <vector>

#include "makeway/common/detection.hpp"

namespace makeway::perception {

struct NmsParams {
    double max_bev_iou =
        0.25;  ///< a box overlapping a kept, higher-scoring one more than this is dropped
    bool per_class = false;  ///< false: a chair and a table cannot share a footprint either
    std::size_t max_detections = 100;
};

/// Keeps the highest-scoring boxes, dropping any whose bird's-eye-view IoU with a kept box exceeds
/// the threshold. Returns the kept detections, best first; ties keep input order.
std::vector<Detection> rotated_nms(std::vector<Detection> detections, const NmsParams& params = {});

}  // namespace makeway::perception
