#pragma once
// Data augmentation for detector training, on the points and their labelled boxes together.
#include <utility>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway::perception {

using LabelledBoxes = std::vector<std::pair<ObjectClass, OrientedBox>>;

/// A rotation about z, a mirror across x, 60-100 % subsampling and, for 30 %
/// of the samples, dropout beyond a range in [4, 8] m (boxes beyond it dropped too).
void augment_sample(PointCloud& cloud, LabelledBoxes& boxes, Rng& rng);

}  // namespace makeway::perception
