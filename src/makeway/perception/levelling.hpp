#pragma once
// The detector's input normalised for how the sensor is mounted (issue 32). The network learns
// chairs and tables in a height band of its input frame; a LiDAR mounted higher, lower or tilted
// puts them elsewhere in that band. The keyframe's fitted ground plane says where the floor is, so
// the cloud goes to the frame of a level sensor at the height the network was trained at, right
// above the real one and facing the same way, and the boxes come back. No height is assumed: it is
// measured per keyframe.
#include <Eigen/Core>
#include <optional>

#include "makeway/common/transforms.hpp"

namespace makeway::perception {

/// T_level_sensor for a ground plane in the sensor frame (n . p + d = 0, n a unit normal pointing
/// up, towards the sensor: d > 0 is the sensor's height): the smallest rotation that turns n onto
/// +z (no turn about the vertical), then a shift along z that puts the floor at z = -height_m.
/// Identity when the plane is not usable (non-finite, a normal of length far from 1, a sensor
/// below the floor or more than 10 m above it).
Isometry3 level_frame(const Eigen::Vector4d& plane_sensor, double height_m);

/// level_frame() when there is a plane and a height to level to (height_m > 0), else nothing: the
/// cloud is used as the sensor gave it.
std::optional<Isometry3> level_frame_if(const std::optional<Eigen::Vector4d>& plane_sensor,
                                        double height_m);

}  // namespace makeway::perception
