#pragma once
// Occlusion by other objects (paper, "Object Tracking"): rays from the sensor to points of an
// object's box tested against the axis-aligned bounding boxes of the other objects.
#include <vector>

#include "makeway/common/oriented_box.hpp"

namespace makeway::tracking {

struct OcclusionParams {
    double blocked_fraction = 0.5;  ///< occluded when at least this share of the rays is blocked
    double shrink = 0.8;            ///< ray targets: centre and box corners pulled toward the centre
};

/// True when the ray from `from` to `to` passes through the axis-aligned box [lo, hi] strictly
/// between its ends (slab test).
bool ray_hits_aabb(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Whether `target` is hidden from `sensor_world` by `others` (which must not contain the target;
/// boxes that contain the sensor are ignored). Targets: the box centre and its 4 footprint corners
/// at mid height, shrunk toward the centre.
bool is_occluded(const Eigen::Vector3d& sensor_world, const OrientedBox& target, const std::vector<OrientedBox>& others,
                 const OcclusionParams& params = {});

}  // namespace makeway::tracking
