#include "makeway/sim/route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace makeway::sim {

Eigen::Vector2i NavGrid::cell_of(const Eigen::Vector2d& p_m) const {
    const Eigen::Vector2d q = (p_m - origin_m) / resolution_m;
    return {static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))};
}

Eigen::Vector2d NavGrid::centre_of(int ix, int iy) const {
    return origin_m + resolution_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

NavGrid make_nav_grid(const Scene& scene, const CollisionChecker& checker, const RobotParams& robot,
                      double t_s, double resolution_m, double inflation_m) {
    if (inflation_m < 0.0) inflation_m = robot.circumscribed_radius_m() + 0.05;
    NavGrid g;
    g.resolution_m = resolution_m;
    g.origin_m = scene.floor_min_m;
    const Eigen::Vector2d extent = scene.floor_max_m - scene.floor_min_m;
    g.width = static_cast<int>(std::ceil(extent.x() / resolution_m));
    g.height = static_cast<int>(std::ceil(extent.y() / resolution_m));
    std::vector<std::uint8_t> obstacle(static_cast<std::size_t>(g.width) * g.height, 0);
    for (const Eigen::Vector2d& p : checker.obstacle_points(t_s)) {
        const Eigen::Vector2i c = g.cell_of(p);
        if (g.inside(c.x(), c.y())) obstacle[c.y() * g.width + c.x()] = 1;
    }
    // Grow every obstacle cell by a disk of the inflation radius.
    const int r = static_cast<int>(std::ceil(inflation_m / resolution_m));
    std::vector<Eigen::Vector2i> disk;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            if (std::hypot(dx, dy) * resolution_m <= inflation_m + 0.5 * resolution_m)
                disk.emplace_back(dx, dy);
        }
    }
    g.blocked.assign(obstacle.size(), 0);
    for (int y = 0; y < g.height; ++y) {
        for (int x = 0; x < g.width; ++x) {
            if (!obstacle[y * g.width + x]) continue;
            for (const auto& d : disk) {
                if (g.inside(x + d.x(), y + d.y()))
                    g.blocked[(y + d.y()) * g.width + x + d.x()] = 1;
            }
        }
    }
    return g;
}

namespace {

bool line_of_sight(const NavGrid& g, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const int steps = static_cast<int>(std::ceil((b - a).norm() / (0.5 * g.resolution_m)));
    for (int i = 0; i <= steps; ++i) {
        const Eigen::Vector2i c =
            g.cell_of(a + (b - a) * (steps ? static_cast<double>(i) / steps : 0.0));
        if (g.is_blocked(c.x(), c.y())) return false;
    }
    return true;
}

}  // namespace

std::optional<std::vector<Eigen::Vector2d>> find_route(const NavGrid& g,
                                                       const Eigen::Vector2d& from_m,
                                                       const Eigen::Vector2d& to_m) {
    const Eigen::Vector2i s = g.cell_of(from_m), t = g.cell_of(to_m);
    if (g.is_blocked(s.x(), s.y()) || g.is_blocked(t.x(), t.y())) return std::nullopt;
    const int n = g.width * g.height;
    std::vector<double> cost(n, std::numeric_limits<double>::infinity());
    std::vector<int> parent(n, -1);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    auto h = [&](int idx) { return std::hypot(idx % g.width - t.x(), idx / g.width - t.y()); };
    const int start = s.y() * g.width + s.x(), goal = t.y() * g.width + t.x();
    cost[start] = 0.0;
    open.emplace(h(start), start);
    while (!open.empty()) {
        const auto [f, idx] = open.top();
        open.pop();
        if (idx == goal) break;
        if (f > cost[idx] + h(idx) + 1e-9) continue;  // stale entry
        const int x = idx % g.width, y = idx / g.width;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                if ((dx || dy) && !g.is_blocked(x + dx, y + dy)) {
                    const int nidx = (y + dy) * g.width + x + dx;
                    const double c = cost[idx] + ((dx && dy) ? std::sqrt(2.0) : 1.0);
                    if (c < cost[nidx]) {
                        cost[nidx] = c;
                        parent[nidx] = idx;
                        open.emplace(c + h(nidx), nidx);
                    }
                }
            }
        }
    }
    if (parent[goal] < 0 && goal != start) return std::nullopt;
    std::vector<Eigen::Vector2d> cells;
    for (int idx = goal; idx >= 0; idx = parent[idx])
        cells.push_back(g.centre_of(idx % g.width, idx / g.width));
    std::reverse(cells.begin(), cells.end());
    cells.front() = from_m;
    cells.back() = to_m;
    // Keep only the points needed to see from one to the next.
    std::vector<Eigen::Vector2d> route{cells.front()};
    std::size_t i = 0;
    while (i + 1 < cells.size()) {
        std::size_t j = cells.size() - 1;
        while (j > i + 1 && !line_of_sight(g, cells[i], cells[j])) --j;
        route.push_back(cells[j]);
        i = j;
    }
    return route;
}

std::optional<std::vector<Eigen::Vector2d>> mission_route(const Scene& scene, const NavGrid& grid) {
    const Eigen::Vector2d start(scene.start.x_m, scene.start.y_m);
    const Eigen::Vector2d mid(scene.waypoint.x_m, scene.waypoint.y_m);
    const Eigen::Vector2d goal(scene.goal.x_m, scene.goal.y_m);
    auto a = find_route(grid, start, mid);
    if (!a) return std::nullopt;
    auto b = find_route(grid, mid, goal);
    if (!b) return std::nullopt;
    a->insert(a->end(), b->begin() + 1, b->end());
    return a;
}

std::optional<std::vector<Eigen::Vector2d>> drive_route(const Scene& scene,
                                                        const CollisionChecker& checker,
                                                        const RobotParams& robot) {
    for (double margin : {0.30, 0.20, 0.10, 0.05}) {
        const NavGrid grid = make_nav_grid(scene, checker, robot, 0.0, 0.05,
                                           robot.circumscribed_radius_m() + margin);
        if (auto route = mission_route(scene, grid)) return route;
    }
    return std::nullopt;
}

double route_length_m(const std::vector<Eigen::Vector2d>& route) {
    double length = 0.0;
    for (std::size_t i = 1; i < route.size(); ++i) length += (route[i] - route[i - 1]).norm();
    return length;
}

}  // namespace makeway::sim
