#pragma once
// Giving way to what the robot knows is moving: a chair someone pulls out from a table comes at
// 0.1-0.2 m/s into whatever stands behind it, and a robot held beside the chair (the stop zone
// forbids only moving *toward* returns) waits to be hit. The collision monitor's give-way
// (give_way_horizon_s, collision_monitor.hpp) weighs its candidate commands by how they keep the
// footprint clear of the moving objects over the horizon.
//
// The geometry here: the distance between the footprint following a predicted motion and outlines
// moving at constant velocity. Straight-line prediction overshoots a pulled chair, which slows
// down at the end of its pull: the robot gives way a little early, not late.
#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "makeway/common/polygon2d.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::planning {

/// An object the robot knows is moving: its outline (any vertex order) and its velocity, in the
/// frame of the caller's poses.
struct MovingOutline {
    Polygon2 outline;
    Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
};

/// Signed distance from `p` to the rectangle with half sizes `half` centred on the origin, axes
/// along x and y (negative inside): the footprint in the base frame. Inline: the collision
/// monitor's zones call it for every return at every step of a motion.
inline double rect_signed_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& half) {
    const Eigen::Vector2d q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(std::max(q.x(), q.y()), 0.0);
}

/// Signed distance between the rectangle with half sizes `half` centred on `pose` (x along its yaw)
/// and the convex polygon `polygon` (either vertex order): apart, the distance; overlapping, minus
/// the depth (the shortest shift that parts them: separating axes); 0 when they just touch.
double rectangle_polygon_distance(const Pose2& pose, const Eigen::Vector2d& half,
                                  const Polygon2& polygon);

/// How a predicted motion keeps clear of moving outlines (signed distances: an outline already on
/// the footprint, a box a little larger than the chair, is negative).
struct Clearance {
    double least_m = std::numeric_limits<double>::infinity();   ///< the least distance on the way
    double within_s = std::numeric_limits<double>::infinity();  ///< first time within the margin
    double final_m = std::numeric_limits<double>::infinity();   ///< the distance at the end
    /// More clearance: within the margin later (or never); both within it from the start (the
    /// mover is on the robot already, and the least distance is now's for every motion): the one
    /// that ends farther out; else farther at the closest.
    bool better_than(const Clearance& o) const {
        if (within_s != o.within_s) return within_s > o.within_s + 1e-9;
        if (within_s <= 0.0 && std::abs(final_m - o.final_m) > 1e-3) return final_m > o.final_m;
        return least_m > o.least_m + 1e-3;
    }
};

/// Over `poses` (time [s], pose of the base), the footprint (half sizes `half`) against each
/// outline carried along its velocity to that time: the least signed distance, the first time it
/// is at most `margin_m`, and the least at the last pose. With no outline or no pose, never and
/// infinitely far.
Clearance clearance_over(const std::vector<std::pair<double, Pose2>>& poses,
                         const Eigen::Vector2d& half, const std::vector<MovingOutline>& movers,
                         double margin_m);

}  // namespace makeway::planning
