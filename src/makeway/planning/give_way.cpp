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
    const Polygon2 hull = local.size() >= 3 ? convex_hull(local) : local;
    if (best > 0.0 && (hull.size() < 3 || std::abs(signed_area(clip_convex(rect, hull))) <= 1e-12))
        return best;
    // Overlapping (or touching): the depth is the least overlap of the two shapes' projections on
    // the axes of their edges (the rectangle's two and the hull's normals).
    std::vector<Eigen::Vector2d> axes{{1.0, 0.0}, {0.0, 1.0}};
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Eigen::Vector2d e = hull[(i + 1) % hull.size()] - hull[i];
        if (e.norm() > 1e-12) axes.emplace_back(-e.y() / e.norm(), e.x() / e.norm());
    }
    double depth = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& n : axes) {
        const double r = std::abs(n.x()) * half.x() + std::abs(n.y()) * half.y();
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Eigen::Vector2d& q : hull) {
            lo = std::min(lo, n.dot(q));
            hi = std::max(hi, n.dot(q));
        }
        depth = std::min(depth, std::min(r - lo, hi + r));
    }
    return -std::max(depth, 0.0);
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
            if (&pose == &poses.back().second) out.final_m = std::min(out.final_m, d);
        }
    }
    return out;
}

}  // namespace makeway::planning
