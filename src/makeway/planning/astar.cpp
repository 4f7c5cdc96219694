#include "makeway/planning/astar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "makeway/planning/param_tables.hpp"

namespace makeway::planning {

namespace {

// A cell A* may enter, and what a metre through it weighs: plan_astar and path_cost share both, so
// a path costed afterwards compares with A*'s own sum.
bool enterable(std::uint8_t c, const AStarParams& params) {
    return c == cost::kUnknown ? params.allow_unknown : c < params.blocked_cost;
}
double weight_per_m(std::uint8_t c, const AStarParams& params) {
    const double soft = c == cost::kUnknown ? cost::kMaxSoft : c;
    return 1.0 + params.cost_weight * soft / cost::kMaxSoft;
}

}  // namespace

std::vector<std::string> AStarParams::validate() const {
    std::vector<std::string> out = astar_table().problems(*this);
    if (blocked_cost == 0) out.push_back("blocked_cost must be > 0");
    return out;
}

std::string_view to_string(PlanStatus s) {
    switch (s) {
        case PlanStatus::kOk:
            return "ok";
        case PlanStatus::kStartBlocked:
            return "start_blocked";
        case PlanStatus::kGoalBlocked:
            return "goal_blocked";
        case PlanStatus::kNoPath:
            return "no_path";
        case PlanStatus::kOutsideMap:
            return "outside_map";
    }
    return "unknown";
}

PlanResult plan_astar(const Costmap& map, const Eigen::Vector2d& start_m,
                      const Eigen::Vector2d& goal_m, const AStarParams& params,
                      double goal_radius_m) {
    PlanResult r;
    const Eigen::Vector2i s = map.cell_of(start_m), g = map.cell_of(goal_m);
    if (!map.inside(s.x(), s.y()) || !map.inside(g.x(), g.y())) {
        r.status = PlanStatus::kOutsideMap;
        return r;
    }
    auto passable = [&](int x, int y) { return enterable(map.at(x, y), params); };
    if (!passable(s.x(), s.y())) {
        r.status = PlanStatus::kStartBlocked;
        return r;
    }
    const double radius = std::max(goal_radius_m, 0.0);
    bool goal_open = passable(g.x(), g.y());
    const int reach = static_cast<int>(std::ceil(radius / map.resolution_m));
    for (int dy = -reach; dy <= reach && !goal_open;
         ++dy) {  // any free cell of the goal's disc will do
        for (int dx = -reach; dx <= reach && !goal_open; ++dx) {
            const int x = g.x() + dx, y = g.y() + dy;
            goal_open = map.inside(x, y) && (map.centre_of(x, y) - goal_m).norm() <= radius &&
                        passable(x, y);
        }
    }
    if (!goal_open) {
        r.status = PlanStatus::kGoalBlocked;
        return r;
    }
    const int w = map.width;
    const std::size_t n = static_cast<std::size_t>(w) * map.height;
    std::vector<double> best(n, std::numeric_limits<double>::infinity());
    std::vector<int> parent(n, -1);
    std::vector<std::uint8_t> closed(n, 0);
    const double res = map.resolution_m;
    auto heuristic = [&](int idx) {  // octile distance [m]
        const double dx = std::abs(idx % w - g.x()), dy = std::abs(idx / w - g.y());
        return std::max(
            0.0, res * (std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy)) - radius);
    };
    auto is_goal = [&](int idx) {
        return radius == 0.0 ? idx == g.y() * w + g.x()
                             : (map.centre_of(idx % w, idx / w) - goal_m).norm() <= radius;
    };
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    const int start = s.y() * w + s.x();
    int goal = -1;
    best[start] = 0.0;
    open.emplace(heuristic(start), start);
    while (!open.empty()) {
        const int idx = open.top().second;
        open.pop();
        if (closed[idx]) continue;
        closed[idx] = 1;
        ++r.expansions;
        if (is_goal(idx)) {
            goal = idx;
            break;
        }
        const int x = idx % w, y = idx / w;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if ((!dx && !dy) || !map.inside(nx, ny) || !passable(nx, ny)) continue;
                const int nidx = ny * w + nx;
                if (closed[nidx]) continue;
                const double step = res * ((dx && dy) ? std::sqrt(2.0) : 1.0);
                const double cand = best[idx] + step * weight_per_m(map.at(nx, ny), params);
                if (cand < best[nidx]) {
                    best[nidx] = cand;
                    parent[nidx] = idx;
                    open.emplace(cand + heuristic(nidx), nidx);
                }
            }
        }
    }
    if (goal < 0) {
        r.status = PlanStatus::kNoPath;
        return r;
    }
    for (int idx = goal; idx >= 0; idx = parent[idx])
        r.path_m.push_back(map.centre_of(idx % w, idx / w));
    std::reverse(r.path_m.begin(), r.path_m.end());
    r.path_m.front() = start_m;
    if (radius == 0.0) r.path_m.back() = goal_m;
    for (std::size_t i = 1; i < r.path_m.size(); ++i)
        r.length_m += (r.path_m[i] - r.path_m[i - 1]).norm();
    r.cost = best[goal];
    r.status = PlanStatus::kOk;
    return r;
}

double path_cost(const Costmap& map, const std::vector<Eigen::Vector2d>& path_m,
                 const AStarParams& params) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const double res = map.resolution_m;
    double total = 0.0;
    for (std::size_t i = 1; i < path_m.size(); ++i) {
        const Eigen::Vector2d a = path_m[i - 1], b = path_m[i];
        const double length = (b - a).norm();
        // A step to a neighbouring cell is one piece (A*'s own); a longer segment is cut into
        // half-cell pieces. Each piece costs at the cell it ends in.
        const int n = length <= 1.5 * res ? 1 : static_cast<int>(std::ceil(length / (0.5 * res)));
        for (int k = 1; k <= n; ++k) {
            const Eigen::Vector2i c = map.cell_of(a + (b - a) * (static_cast<double>(k) / n));
            if (!map.inside(c.x(), c.y())) return kInf;
            const std::uint8_t v = map.at(c.x(), c.y());
            if (!enterable(v, params)) return kInf;
            total += length / n * weight_per_m(v, params);
        }
    }
    return total;
}

}  // namespace makeway::planning
