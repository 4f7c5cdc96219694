#pragma once
// Detector datasets on disk: DIR/clouds/NNNNNN.bin (KITTI x y z intensity, sensor frame, ground
// and ceiling removed) and DIR/labels/NNNNNN.json ({"objects": [{"id", "class", "style", "box",
// "points"}], "unseen": [...], "sequence", "stamp_s", "T_world_sensor": {"t_m", "q_wxyz"}}, boxes
// in the same frame; all but "objects" optional). Auto-labelled real data uses the same layout.
#include <filesystem>
#include <functional>
#include <vector>

#include "makeway/common/labelled_keyframe.hpp"

namespace makeway::io {

void write_labelled_keyframe(const std::filesystem::path& dir, std::size_t index,
                             const LabelledKeyframe& keyframe);
/// Every keyframe of a dataset folder; throws FileError naming the file on bad input.
std::vector<LabelledKeyframe> read_detection_dataset(
    const std::filesystem::path& dir,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace makeway::io
