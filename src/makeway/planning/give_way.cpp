#include "makeway/planning/give_way.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace makeway::planning {

double rectangle_polygon_distance(const Pose2& pose, const Eigen::Vector2d& half,
                                  const Polygon2& polygon) {
    if (polygon.empty()) return std::numeric_limits<double>::infinity();
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    Polygon2 local;
    local.reserve(polygon.size());
    for (const Eigen::Vector2d& q : polygon) {
        const Eigen::Vector2d d = q - Eigen::Vector2d(pose.x_m, pose.y_m);
        local.emplace_back(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    }
    const Polygon2 rect{
        {-half.x(), -half.y()}, {half.x(), -half.y()}, {half.x(), half.y()}, {-half.x(), half.y()}};
    // Apart, two convex shapes are nearest at a vertex of one against the other.
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& q : local)
        best = std::min(best, std::max(rect_signed_distance(q, half), 0.0));
    for (const Eigen::Vector2d& corner : rect)
        best = std::min(best, convex_distance(local, corner));
    // Crossing like a plus sign, neither holds a vertex of the other.
    if (best > 0.0 && local.size() >= 3 &&
        std::abs(signed_area(clip_convex(rect, convex_hull(local)))) > 1e-12)
        return 0.0;
    return best;
}

Clearance clearance_over(const std::vector<std::pair<double, Pose2>>& poses,
                         const Eigen::Vector2d& half, const std::vector<MovingOutline>& movers,
                         double margin_m) {
    Clearance out;
    Polygon2 moved;
    for (const MovingOutline& m : movers) {
        for (const auto& [t, pose] : poses) {
            moved.clear();
            for (const Eigen::Vector2d& q : m.outline) moved.push_back(q + t * m.velocity_mps);
            const double d = rectangle_polygon_distance(pose, half, moved);
            out.least_m = std::min(out.least_m, d);
            if (d <= margin_m) out.within_s = std::min(out.within_s, t);
        }
    }
    return out;
}

}  // namespace makeway::planning
