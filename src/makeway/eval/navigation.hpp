#pragma once
// Closed-loop navigation on the simulator: the Jackal drives start -> waypoint -> goal while the
// LiDAR sweeps (the robot moves during each sweep, as a real one does). Every method shares the
// online Navigator (pipeline/navigator.hpp); they differ in inflation, in whether the costmap is
// object-aware, and in what feeds it:
//   con, oppo, gt-perc: the simulator's true pose (and, for gt-perc, its true objects);
//   ours: the online Pipeline, fed only what a robot has (sweeps, drifting wheel odometry, the
//         start pose, the map of walls, the CAD models of the room's furniture).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "makeway/eval/map_sanity.hpp"
#include "makeway/eval/object_source.hpp"
#include "makeway/perception/object_detector.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/pipeline/pipeline.hpp"
#include "makeway/pipeline/system_params.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/sim/contact_judge.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/shape_prior.hpp"

namespace makeway::eval {

/// con: no semantics, the robot taken 3x its size (the planner keeps 3x its inscribed radius from
/// everything, and inflation reaches 3x its circumscribed radius), so it cannot pass where a robot
/// of that size could not, as the paper's conservative planner; oppo: no semantics, inflation =
/// robot radius; gt-perc: affordance zones from ground-truth objects; ours: the same zones from the
/// online pipeline on its own pose. The robot radius is the circumscribed one. nav_method_names()
/// lists the methods that need no trained model.
struct NavMethod {
    std::string name;
    double inflation_radius_m = 0.333;
    double inscribed_scale = 1.0;  ///< the planner's keep-out (the inflation's inscribed radius) in
                                   ///< robot inscribed radii
    bool affordance = false;
    bool online = false;  ///< the full system: pipeline perception and pose, no ground truth
};
std::optional<NavMethod> nav_method(std::string_view name, const sim::RobotParams& robot = {});
const std::vector<std::string>& nav_method_names();

struct NavParams {
    sim::LidarParams lidar;
    sim::RobotParams robot;
    sim::OdometryNoiseParams odometry;  ///< the wheel odometry's drift (what `ours` drives on)
    pipeline::SystemParams
        system;  ///< the online system; navigator.inflation radius is the method's
    double resolution_m = 0.05;
    double time_limit_s = 180.0;
    double near_miss_m = 0.25;
    double robot_caused_speed_mps =
        0.05;  ///< a contact is the robot's when it moved toward it faster than this  ///< robot
               ///< body this close to a chair being moved: a near-miss
    /// The judge of arrival: the robot stops when it believes it is within the navigator's goal
    /// tolerance (0.3 m); the run has arrived when its true centre is within this of the goal then.
    /// Truth-fed methods stop within 0.3 m for real; the margin is the full system's pose error
    /// (wheel odometry drifts about 2 cm per metre), reported per run as final_pose_error_m.
    double arrival_radius_m = 0.5;
    int physics_steps = 10;  ///< robot and scoring steps per sweep
    std::uint64_t seed = 0;
    /// The static layer's map (e.g. a map_server map); its geometry becomes the costmap's. When
    /// absent, the scene's walls and pillars are rasterised at resolution_m.
    std::optional<Costmap> static_map;
    /// Called once per sweep; may throw to abandon the run (the program checks for Ctrl-C here).
    std::function<void()> on_sweep;
    /// The zones risk time is scored against (`bench nav --risk-zones`); none: the navigator's own
    /// (system.navigator.affordance, the paper's shapes unless a zones file replaced them: then
    /// set this to the shapes the methods are compared on).
    std::optional<costmap::AffordanceParams> risk_zones;
    const costmap::AffordanceParams& scored_zones() const {
        return risk_zones ? *risk_zones : system.navigator.affordance;
    }
};

/// The map's objects after one keyframe of the online system.
struct KeyframeObjects {
    double stamp_s = 0.0;
    Isometry3 T_world_keyframe = Isometry3::Identity();  ///< estimated
    std::size_t detections = 0, accepted = 0;
    std::vector<ObjectEstimate> objects;
};

/// How contacts are judged: sim/contact_judge.hpp, shared with the ROS sim node.
using sim::ContactCounts;
using sim::ContactEvent;
using sim::robot_caused_contact;
using sim::speed_toward_contact;

struct NavRunResult {
    std::string method;
    bool success = false;  ///< goal reached in time without colliding with structure or furniture
    bool reached_goal =
        false;  ///< the robot stopped within arrival_radius_m of the goal (true position)
    double stop_distance_m = 0.0;  ///< true distance from the goal where the robot stopped
    std::string failure;           ///< why not, when not
    bool gave_up = false;  ///< the navigator gave up (no plan or no progress for its give_up_s)
    double time_s = 0.0;   ///< total time to goal (or to the end of the run)
    double distance_m = 0.0;
    double risk_time_s =
        0.0;  ///< time with the robot's centre inside a ground-truth affordance zone
    /// The least risk time any collision-free route (start, waypoint, goal within the navigator's
    /// tolerances) must have at top speed, furniture where it stands at the start
    /// (unavoidable_risk.hpp); -1 when the truth has no route. avoidable = risk - this.
    double unavoidable_risk_s = 0.0;
    int collisions = 0;  ///< contacts with walls, pillars or furniture (counted when they start)
    int person_contacts = 0;  ///< contacts with walking people (who do not avoid the robot)
    int near_misses = 0;      ///< a moving chair within near_miss_m of the robot's body
    ContactCounts wall_contacts, furniture_contacts, people_contacts;  ///< by who caused them
    std::vector<ContactEvent> contact_events;
    /// The collision monitor per control cycle (none, slowdown, approach, stop, recovery_backup,
    /// recovery_rotate, blocked, give_way), and the cycles it spent on each.
    std::vector<planning::MonitorAction> monitor_actions;
    std::vector<std::string>
        nav_states;  ///< the navigator per control cycle (pipeline::to_string_state)
    std::vector<VelocityCommand>
        commands;  ///< the command sent to the motors per control cycle (after the monitor)
    /// Risk time per sweep period, the last (arriving or giving-up) one included: where the
    /// risk accrued.
    std::vector<double> cycle_risk_s;
    double monitor_ms_max =
        0.0;  ///< the slowest collision monitor cycle (timing.json; included in cycle_ms)
    double min_clearance_m = 0.0;
    double shortest_m = 0.0;  ///< shortest collision-free route length start -> waypoint -> goal
    double spl = 0.0;         ///< success weighted by shortest / driven length
    int replans = 0;
    int recoveries = 0;
    std::vector<Pose2> trajectory;            ///< true, one per sweep
    std::vector<Pose2> estimated_trajectory;  ///< what the robot believed, one per sweep
    double final_pose_error_m = 0.0;          ///< |estimated - true| position at the end
    double pose_ate_m =
        0.0;  ///< RMSE of |estimated - true| position over the run (the odometry's ATE)
    std::vector<double> cycle_ms;  ///< costmap update + planning + DWA per control cycle
    std::vector<pipeline::StageTiming> keyframe_timing;  ///< online system only
    std::vector<KeyframeObjects> keyframes;              ///< online system only
    MapSanity map_sanity;  ///< online system only: phantoms in its map
    Costmap final_costmap;
    std::vector<Eigen::Vector2d> last_plan;
};

/// A truth-fed method (con, oppo, gt-perc): the true pose and `source`'s objects.
NavRunResult run_navigation(const sim::Scene& scene, const NavMethod& method, ObjectSource& source,
                            const NavParams& params);
/// The online system `ours` drives in `scene`, as run_navigation_online builds it (no detector,
/// library or prior set): the method's navigator on NavParams' system, the scene's walls as the
/// map.
pipeline::OnlineSystemSetup online_system_setup(const sim::Scene& scene, const NavMethod& method,
                                                const NavParams& params);

/// The full system (ours): the online pipeline with `detector` and the CAD `library` (may be null),
/// and a learned shape prior for detections no CAD model fits (may be null).
NavRunResult run_navigation_online(const sim::Scene& scene, const NavMethod& method,
                                   const perception::ObjectDetector& detector,
                                   const verification::CadLibrary* library, const NavParams& params,
                                   const verification::ShapePrior* prior = nullptr);

}  // namespace makeway::eval
