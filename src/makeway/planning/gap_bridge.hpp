#pragma once
// Narrow gaps between returns, closed (the collision monitor's bridge_gap_m): a surface the sensor
// sees edge-on returns nothing (a chair's seat at the sensor's height, between the two posts of its
// back), so two returns closer than anything the robot fits through, with nothing between them,
// stand for one surface.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace makeway::planning {

/// A 2D cell's key in a hash set (unsigned: no shift of a negative index).
inline std::int64_t cell_key(std::int64_t ix, std::int64_t iy) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(ix) << 32) ^
                                     (static_cast<std::uint64_t>(iy) & 0xffffffffULL));
}

/// The points, every step_m, of the segments between two of `pts` at most gap_m apart whose middle
/// has no point of `pts` in the 3 x 3 cells (step_m wide) around it; one per such cell, none in a
/// cell a point of `pts` holds. Pairs over 2 step_m apart only (closer points are one surface
/// already). Each point meets only those in the neighbouring cells gap_m wide: the caller hands
/// the returns near the robot.
std::vector<Eigen::Vector2d> bridge_gaps(const std::vector<Eigen::Vector2d>& pts, double gap_m,
                                         double step_m);

}  // namespace makeway::planning
