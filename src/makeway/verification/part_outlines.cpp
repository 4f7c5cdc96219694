#include "makeway/verification/part_outlines.hpp"

#include <cmath>
#include <map>
#include <utility>

namespace makeway::verification {

std::vector<Polygon2> part_outlines(const std::vector<Eigen::Vector3d>& points_object,
                                    const BodyHeights& body, double cell_m) {
    using Cell = std::pair<long, long>;
    std::map<Cell, std::vector<Eigen::Vector2d>> cells;  // ordered: the result is deterministic
    if (!(cell_m > 0.0)) return {};
    for (const Eigen::Vector3d& p : points_object) {
        if (!p.allFinite() || !body.can_hit(p.z())) continue;
        cells[{std::lround(std::floor(p.x() / cell_m)), std::lround(std::floor(p.y() / cell_m))}]
            .push_back(p.head<2>());
    }
    std::vector<Polygon2> out;
    std::map<Cell, bool> visited;
    for (const auto& [start, unused] : cells) {
        if (visited[start]) continue;
        // One part: the cells reachable through occupied neighbours.
        Polygon2 points;
        std::vector<Cell> queue{start};
        visited[start] = true;
        Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
        while (!queue.empty()) {
            const Cell c = queue.back();
            queue.pop_back();
            for (const Eigen::Vector2d& q : cells.at(c)) points.push_back(q);
            lo = lo.cwiseMin(Eigen::Vector2d(c.first, c.second) * cell_m);
            hi = hi.cwiseMax(Eigen::Vector2d(c.first + 1, c.second + 1) * cell_m);
            for (long dx = -1; dx <= 1; ++dx) {
                for (long dy = -1; dy <= 1; ++dy) {
                    const Cell n{c.first + dx, c.second + dy};
                    if (cells.count(n) && !visited[n]) {
                        visited[n] = true;
                        queue.push_back(n);
                    }
                }
            }
        }
        Polygon2 hull = convex_hull(std::move(points));
        if (hull.size() < 3)  // a thin post sampled in a line: its cells' extent
            hull = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
        out.push_back(std::move(hull));
    }
    return out;
}

}  // namespace makeway::verification
