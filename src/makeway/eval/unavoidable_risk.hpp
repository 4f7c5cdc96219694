#pragma once
// The unavoidable part of the risk metric: the least time inside affordance zones that any route
// from the start through every leg (waypoint, then goal, each reached within its tolerance) must
// spend at the robot's top speed. Risk is then judged as avoidable = measured - unavoidable: a
// goal inside a table's sitting zone, or a corridor that is all zone, costs every method the same.
//
// The search is Dijkstra over the ground-truth navigability grid with a lexicographic cost (metres
// inside zones first, then metres in all), one pass per leg, each leg seeded with the cost of
// every cell the previous one accepted. The grid is grown by the robot's inscribed radius only, a
// necessary condition for any collision-free pose, so the result is a lower bound: no driven route
// can do better, and "avoidable" is never understated.
#include <optional>
#include <vector>

#include "makeway/common/object_estimate.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/sim/route.hpp"

namespace makeway::eval {

struct RouteLeg {
    Eigen::Vector2d target_m = Eigen::Vector2d::Zero();
    double tolerance_m = 0.0;  ///< the leg is done anywhere within this of the target
};

struct LeastRiskRoute {
    bool reachable = false;  ///< false: some leg cannot be reached at all (then everything is 0)
    double zone_length_m = 0.0;  ///< the least length inside zones, over every route
    double length_m = 0.0;       ///< the shortest length among the routes with that zone length
    std::vector<Eigen::Vector2d> cells_m;  ///< the route, cell centres from the start
};

/// `in_zone`: one flag per grid cell (row-major, like grid.blocked). A step between two cells is
/// inside a zone by the half of it that lies in each cell.
LeastRiskRoute least_risk_route(const sim::NavGrid& grid, const std::vector<std::uint8_t>& in_zone,
                                const Eigen::Vector2d& start_m, const std::vector<RouteLeg>& legs);

/// Which cells of `grid` lie inside any object's zone (costmap/affordance.hpp's definition).
std::vector<std::uint8_t> zone_cells(const sim::NavGrid& grid,
                                     const std::vector<ObjectEstimate>& objects,
                                     const costmap::AffordanceParams& params);

struct UnavoidableRisk {
    bool reachable = false;
    double risk_time_s = 0.0;  ///< zone length at the robot's top speed
    double zone_length_m = 0.0;
    double length_m = 0.0;
};

/// The scene at t = 0 (its furniture where it stands), its start, waypoint and goal, the robot's
/// inscribed radius and top speed.
UnavoidableRisk unavoidable_risk(const sim::Scene& scene, const sim::CollisionChecker& checker,
                                 const std::vector<ObjectEstimate>& objects,
                                 const sim::RobotParams& robot,
                                 const costmap::AffordanceParams& zones,
                                 double waypoint_tolerance_m, double goal_tolerance_m,
                                 double resolution_m = 0.05);

}  // namespace makeway::eval
