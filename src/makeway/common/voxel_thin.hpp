#pragma once
// One point per voxel: ICP's coarse levels and the ground plane's area score.
#include <Eigen/Core>
#include <vector>

namespace makeway {

/// Keeps the first finite point of every voxel of size voxel_m [m], in input order.
std::vector<Eigen::Vector3d> voxel_thin(const std::vector<Eigen::Vector3d>& points, double voxel_m);

}  // namespace makeway
