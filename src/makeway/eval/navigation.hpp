#pragma once
// Closed-loop navigation on the simulator: the Jackal drives start -> waypoint -> goal at 10 Hz
// with the layered costmap, A* and DWA, while the LiDAR sweeps. One method differs from another
// only in its inflation radius and its object source (none or ground truth, later perception).
#include <optional>
#include <string>
#include <vector>

#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/eval/object_source.hpp"
#include "makeway/planning/astar.hpp"
#include "makeway/planning/dwa.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"

namespace makeway::eval {

/// con: no semantics, inflation 3x the robot radius; oppo: no semantics, inflation = robot radius;
/// gt-perc: affordance zones from ground-truth objects; ours: the same from the perception chain
/// (detector, verification, tracking; eval/perception_source.hpp). The robot radius is the
/// circumscribed one. nav_method_names() lists the methods that need no trained model.
struct NavMethod {
    std::string name;
    double inflation_radius_m = 0.333;
    bool affordance = false;
};
std::optional<NavMethod> nav_method(std::string_view name, const sim::RobotParams& robot = {});
const std::vector<std::string>& nav_method_names();

struct NavParams {
    sim::LidarParams lidar;
    sim::RobotParams robot;
    costmap::ObstacleLayerParams obstacle;
    costmap::InflationParams inflation;  ///< inflation_radius_m is the method's
    costmap::AffordanceParams affordance;
    planning::AStarParams astar;
    planning::DwaParams dwa;
    double resolution_m = 0.05;
    double replan_period_s = 1.0;
    double time_limit_s = 180.0;
    double waypoint_tolerance_m = 0.5;
    double goal_tolerance_m = 0.3;
    double near_miss_m = 0.25;  ///< robot body this close to a chair being moved: a near-miss
    std::uint64_t seed = 0;
    /// The static layer's map (e.g. a map_server map); its geometry becomes the costmap's. When
    /// absent, the scene's walls and pillars are rasterised at resolution_m.
    std::optional<Costmap> static_map;
};

struct NavRunResult {
    std::string method;
    bool success = false;       ///< goal reached in time without colliding with structure or furniture
    bool reached_goal = false;
    std::string failure;        ///< why not, when not
    double time_s = 0.0;        ///< total time to goal (or to the end of the run)
    double distance_m = 0.0;
    double risk_time_s = 0.0;   ///< time with the robot's centre inside a ground-truth affordance zone
    int collisions = 0;         ///< contacts with walls, pillars or furniture (counted when they start)
    int person_contacts = 0;    ///< contacts with walking people (who do not avoid the robot)
    int near_misses = 0;        ///< a moving chair within near_miss_m of the robot's body
    double min_clearance_m = 0.0;
    double shortest_m = 0.0;    ///< shortest collision-free route length start -> waypoint -> goal
    double spl = 0.0;           ///< success weighted by shortest / driven length
    int replans = 0;
    int recoveries = 0;
    std::vector<Pose2> trajectory;   ///< at 10 Hz
    std::vector<double> cycle_ms;    ///< costmap update + planning + DWA per control cycle
    Costmap final_costmap;
    std::vector<Eigen::Vector2d> last_plan;
};

NavRunResult run_navigation(const sim::Scene& scene, const NavMethod& method, ObjectSource& source,
                            const NavParams& params);

}  // namespace makeway::eval
