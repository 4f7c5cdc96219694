#pragma once
// Global planning: A* on the costmap, 8-connected. A step costs its length times
// (1 + cost_weight * cost / 252); cells at or above `blocked_cost` (inscribed, lethal) and unknown
// cells (unless allowed) cannot be entered. The octile heuristic is admissible for this cost.
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"

namespace makeway::planning {

struct AStarParams {
    double cost_weight = 30.0;
    std::uint8_t blocked_cost = cost::kInscribed;
    bool allow_unknown = false;
    std::vector<std::string> validate() const;
};

enum class PlanStatus { kOk, kStartBlocked, kGoalBlocked, kNoPath, kOutsideMap };

struct PlanResult {
    PlanStatus status = PlanStatus::kNoPath;
    std::vector<Eigen::Vector2d>
        path_m;         ///< cell centres from start to goal (ends replaced by the exact points)
    double cost = 0.0;  ///< the objective, in metres-equivalent
    double length_m = 0.0;
    std::size_t expansions = 0;
};

std::string_view to_string(PlanStatus status);

/// `goal_radius_m` > 0: any cell whose centre lies within it of the goal ends the search (a goal
/// inside an affordance zone is then reached from its cheapest side); the path ends at that cell's
/// centre. kGoalBlocked when no cell of the disc can be entered.
PlanResult plan_astar(const Costmap& costmap, const Eigen::Vector2d& start_m,
                      const Eigen::Vector2d& goal_m, const AStarParams& params = {},
                      double goal_radius_m = 0.0);

/// The objective plan_astar minimises, of any polyline: each step's length times
/// (1 + cost_weight * cost / 252) of the cell it ends in; a segment longer than a step to a
/// neighbouring cell is cut into half-cell pieces. A path as plan_astar returns it costs what A*
/// summed. Infinite where a piece ends in a cell A* may not enter (blocked, unknown unless
/// allowed, outside the map). Fewer than two points cost 0.
double path_cost(const Costmap& costmap, const std::vector<Eigen::Vector2d>& path_m,
                 const AStarParams& params = {});

}  // namespace makeway::planning
