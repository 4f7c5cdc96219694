#pragma once
// What of a CAD model the robot's body can hit, seen from above: the parts between the body's
// ground clearance and its top, each part's outline a convex polygon in the object frame.
//
// A LiDAR cannot see the low parts of furniture near it (a round table's 3 cm foot, an office
// chair's star base: below its lowest beam within about a metre), and a part seen once is not a
// part seen again. An object verified against its CAD model needs no sight of them: the model
// says where they are. Parts are the points' connected pieces on a grid of `cell_m` (8
// neighbours), so a rectangular table gives four leg outlines (the robot passes between them,
// under the top), a chair with its seat in the band one outline, a pedestal table its foot's.
#include <Eigen/Core>
#include <vector>

#include "makeway/common/polygon2d.hpp"
#include "makeway/common/robot_body.hpp"

namespace makeway::verification {

/// Outlines (convex, counter-clockwise) of the parts of a surface sampled at `points_object`
/// that lie in the body's height band; a part of one or two cells becomes its cells' square.
/// Empty when no point is in the band. Deterministic: ordered by the parts' lowest cell.
std::vector<Polygon2> part_outlines(const std::vector<Eigen::Vector3d>& points_object,
                                    const BodyHeights& body, double cell_m = 0.04);

}  // namespace makeway::verification
