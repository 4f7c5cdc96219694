#pragma once
// Ground truth and the object-map stage for labelled keyframe sequences: what the detection
// evaluation's ablation scores (network, + verification, + tracking).
#include <vector>

#include "makeway/common/labelled_keyframe.hpp"
#include "makeway/eval/detection_metrics.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::eval {

/// Ground truth of a keyframe for the metrics (round tables and stools: yaw not scored).
std::vector<LabelledBox> ground_truth_of(const LabelledKeyframe& keyframe);
/// Ground truth for an object map after each keyframe: every labelled object, plus the unseen
/// objects in range whose id was labelled in an earlier keyframe of the same sequence (a map
/// remembers what it saw). Keyframes must be grouped by sequence, in time order.
std::vector<std::vector<LabelledBox>> map_ground_truth_of(
    const std::vector<LabelledKeyframe>& keyframes);

/// One object map per sequence fed with `detections[i]` at keyframe i; returns the map's objects
/// in each keyframe's sensor frame within `range_m` (|x| and |y|, as labelled), scored by
/// existence.
std::vector<std::vector<Detection>> track_keyframes(
    const std::vector<LabelledKeyframe>& keyframes,
    const std::vector<std::vector<Detection>>& detections, const tracking::TrackerParams& params,
    double range_m);

}  // namespace makeway::eval
