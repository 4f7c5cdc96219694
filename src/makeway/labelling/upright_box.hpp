#pragma once
// The paper's bounding-box step: an upright oriented box around a cluster from the PCA of its
// footprint. Furniture stands on the floor, so only the yaw is estimated (the principal axis of the
// points' horizontal spread); the box is then the tight extent along that axis and its normal, and
// vertically from the floor (when known) or the lowest point to the highest.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "makeway/common/oriented_box.hpp"

namespace makeway::labelling {

/// Yaw in (-pi/2, pi/2]: the box's x runs along the larger horizontal spread. An empty cluster
/// gives a zero-size box at the origin; a cluster without horizontal spread (a single vertical
/// line) yaw 0. `floor_z_m` extends the box down to the floor (objects stand on it).
OrientedBox upright_pca_box(const std::vector<Eigen::Vector3d>& points,
                            std::optional<double> floor_z_m = std::nullopt);

}  // namespace makeway::labelling
