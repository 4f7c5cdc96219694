#include "makeway/eval/unavoidable_risk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace makeway::eval {
namespace {

// Lexicographic cost: metres inside zones, then metres. Zone lengths that differ by rounding
// alone (the same steps summed in another order) count as equal.
struct Cost {
    double zone = std::numeric_limits<double>::infinity();
    double length = std::numeric_limits<double>::infinity();
    bool operator<(const Cost& o) const {
        constexpr double kTie = 1e-9;
        return zone < o.zone - kTie || (zone <= o.zone + kTie && length < o.length);
    }
    bool finite() const { return std::isfinite(zone); }
};

}  // namespace

LeastRiskRoute least_risk_route(const sim::NavGrid& g, const std::vector<std::uint8_t>& in_zone,
                                const Eigen::Vector2d& start_m, const std::vector<RouteLeg>& legs) {
    LeastRiskRoute out;
    const std::size_t n = static_cast<std::size_t>(g.width) * g.height;
    if (in_zone.size() != n || legs.empty()) return out;
    const Eigen::Vector2i s = g.cell_of(start_m);
    if (g.is_blocked(s.x(), s.y())) return out;
    // One Dijkstra per leg; cost[k] and parent[k] are leg k's, seeds carry leg k-1's costs.
    std::vector<Cost> seed(n);
    seed[s.y() * g.width + s.x()] = {0.0, 0.0};
    std::vector<std::vector<int>> parents;
    std::vector<std::vector<Cost>> costs;
    std::vector<int>
        accept_best;  // per leg: the accepted cell the next leg continues from (filled at the end)
    for (const RouteLeg& leg : legs) {
        std::vector<Cost> cost = seed;
        std::vector<int> parent(n, -1);
        using Entry = std::pair<Cost, int>;
        auto later = [](const Entry& a, const Entry& b) { return b.first < a.first; };
        std::priority_queue<Entry, std::vector<Entry>, decltype(later)> open(later);
        for (std::size_t i = 0; i < n; ++i) {
            if (cost[i].finite()) open.emplace(cost[i], static_cast<int>(i));
        }
        while (!open.empty()) {
            const auto [c, idx] = open.top();
            open.pop();
            if (cost[idx] < c) continue;  // stale
            const int x = idx % g.width, y = idx / g.width;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    if ((!dx && !dy) || g.is_blocked(x + dx, y + dy)) continue;
                    const int nidx = (y + dy) * g.width + x + dx;
                    const double step = g.resolution_m * ((dx && dy) ? std::sqrt(2.0) : 1.0);
                    const Cost cand{c.zone + 0.5 * step * (in_zone[idx] + in_zone[nidx]),
                                    c.length + step};
                    if (cand < cost[nidx]) {
                        cost[nidx] = cand;
                        parent[nidx] = idx;
                        open.emplace(cand, nidx);
                    }
                }
            }
        }
        // The cells that finish the leg seed the next one.
        std::vector<Cost> next(n);
        bool any = false;
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d c =
                g.centre_of(static_cast<int>(i % g.width), static_cast<int>(i / g.width));
            if (cost[i].finite() &&
                (c - leg.target_m).norm() <= leg.tolerance_m + 0.5 * g.resolution_m) {
                next[i] = cost[i];
                any = true;
            }
        }
        if (!any) return out;
        costs.push_back(std::move(cost));
        parents.push_back(std::move(parent));
        seed = std::move(next);
    }
    int best = -1;
    for (std::size_t i = 0; i < n; ++i) {
        if (seed[i].finite() && (best < 0 || seed[i] < seed[best])) best = static_cast<int>(i);
    }
    out.reachable = true;
    out.zone_length_m = seed[best].zone;
    out.length_m = seed[best].length;
    // Walk back leg by leg: within a leg follow parents until a seed (a cell with no parent).
    std::vector<Eigen::Vector2d> cells;
    int idx = best;
    for (std::size_t k = parents.size(); k-- > 0;) {
        while (parents[k][idx] >= 0) {
            cells.push_back(g.centre_of(idx % g.width, idx / g.width));
            idx = parents[k][idx];
        }
    }
    cells.push_back(g.centre_of(idx % g.width, idx / g.width));
    std::reverse(cells.begin(), cells.end());
    out.cells_m = std::move(cells);
    return out;
}

std::vector<std::uint8_t> zone_cells(const sim::NavGrid& g,
                                     const std::vector<ObjectEstimate>& objects,
                                     const costmap::AffordanceParams& params) {
    std::vector<std::uint8_t> in(static_cast<std::size_t>(g.width) * g.height, 0);
    for (const ObjectEstimate& o : objects) {
        Eigen::Vector2d lo, hi;
        costmap::zone_bounds(o, params, lo, hi);
        const Eigen::Vector2i a = g.cell_of(lo), b = g.cell_of(hi);
        for (int y = std::max(0, a.y()); y <= std::min(g.height - 1, b.y()); ++y) {
            for (int x = std::max(0, a.x()); x <= std::min(g.width - 1, b.x()); ++x) {
                if (costmap::in_affordance_zone(o, params, g.centre_of(x, y)))
                    in[y * g.width + x] = 1;
            }
        }
    }
    return in;
}

UnavoidableRisk unavoidable_risk(const sim::Scene& scene, const sim::CollisionChecker& checker,
                                 const std::vector<ObjectEstimate>& objects,
                                 const sim::RobotParams& robot,
                                 const costmap::AffordanceParams& zones,
                                 double waypoint_tolerance_m, double goal_tolerance_m,
                                 double resolution_m) {
    const sim::NavGrid grid =
        sim::make_nav_grid(scene, checker, robot, 0.0, resolution_m, robot.inscribed_radius_m());
    const LeastRiskRoute r =
        least_risk_route(grid, zone_cells(grid, objects, zones), {scene.start.x_m, scene.start.y_m},
                         {{{scene.waypoint.x_m, scene.waypoint.y_m}, waypoint_tolerance_m},
                          {{scene.goal.x_m, scene.goal.y_m}, goal_tolerance_m}});
    UnavoidableRisk out;
    out.reachable = r.reachable;
    out.zone_length_m = r.zone_length_m;
    out.length_m = r.length_m;
    out.risk_time_s = r.zone_length_m / robot.max_v_mps;
    return out;
}

}  // namespace makeway::eval
