#pragma once
// Every parameter of the online system in one struct (KISS-ICP's one config with defaults),
// validated once at start-up with every problem listed. config/default.yaml documents each key.
#include <string>
#include <vector>

#include "makeway/common/robot_description.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/odometry/lidar_odometry.hpp"
#include "makeway/perception/ground.hpp"
#include "makeway/pipeline/tracked_shapes.hpp"
#include "makeway/planning/astar.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/planning/dwa.hpp"
#include "makeway/tracking/object_map.hpp"
#include "makeway/verification/back_yaw.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::pipeline {

/// Sweeps into keyframes (paper, front end): the last `window` sweeps, de-skewed and accumulated
/// into the newest sweep's frame, every `every` sweeps (10 Hz sweeps: 2 Hz keyframes).
struct KeyframeParams {
    int window = 5;
    int every = 5;
    bool deskew = true;
    perception::GroundPlaneParams ground;          ///< RANSAC, once, at the first keyframe
    perception::GroundFilterParams ground_filter;  ///< ground band and ceiling removed
    std::vector<std::string> validate() const;
};

/// The navigation policy around the costmap, A* and DWA: when to replan and how to recover.
struct NavigatorParams {
    costmap::ObstacleLayerParams obstacle;
    costmap::InflationParams inflation;  ///< inflation_radius_m: the method's (con: 3x the robot)
    bool affordance_layer = true;        ///< object-aware zones (false: the classic costmap)
    costmap::AffordanceParams affordance;
    planning::AStarParams astar;
    planning::DwaParams dwa;
    /// Between the navigator and the motors, on the raw sweep (the footprint and the body from the
    /// robot description; config section `collision_monitor`).
    planning::CollisionMonitorParams monitor;
    double replan_period_s = 1.0;  ///< the global plan is renewed at least this often
    /// A renewed plan replaces the one being followed, while that one is still free, only when the
    /// rest of the old one costs more than (1 + plan_switch_margin) times the new one (A*'s
    /// objective, on the same map). 0: always the newest plan. Two ways of nearly equal cost (the
    /// two sides of a row of chairs) otherwise alternate as a walker or a new zone tips the
    /// balance, and the robot turns back and forth at the fork until it gives up. 0.3 on 200
    /// scenes: `ours` 193 -> 195 successes, no robot-caused contact; 0.15 gains nothing (README,
    /// Table II's eighteenth and nineteenth passes).
    double plan_switch_margin = 0.3;
    double blocked_lookahead_m =
        3.0;  ///< a lethal cell on the plan this far ahead forces a replan ...
    double blocked_ignore_m =
        0.3;  ///< ... unless it is this close to the robot (under its own body)
    int turn_target_index =
        3;  ///< DWA finds nothing: turn on the spot toward this plan point (cells from its start)
    double turn_rate_radps = 1.0;
    /// The turn on the spot only where the bare footprint, turned this far, stays off the
    /// costmap's lethal cells (else none: the stuck recovery); 0: unchecked. Off by
    /// default: 0.5 on 200 scenes moved robot-caused contacts between methods rather than
    /// removing them (README, Table II's twentieth pass).
    double turn_clear_rad = 0.0;
    double stuck_progress_m = 0.3;  ///< the way left along the plan shrinking by less than this ...
    double stuck_timeout_s = 6.0;   ///< ... for this long means stuck: back up and replan
    double backup_speed_mps = 0.15;
    double backup_duration_s = 1.0;
    double standstill_timeout_s =
        2.0;  ///< DWA's best velocity a standstill this long: stuck now (back up and replan)
    double standstill_v_mps = 0.01;     ///< standstill: slower than this ...
    double standstill_w_radps = 0.05;   ///< ... turning slower than this
    double waypoint_tolerance_m = 0.5;  ///< a waypoint counts as reached this close
    double goal_tolerance_m = 0.3;  ///< the goal counts as reached this close (own pose estimate)
    double give_up_s =
        20.0;  ///< no plan found, or no progress despite recoveries, this long: the mission fails
    /// Stuck means the plan leads where the robot cannot go (a gap its footprint does not turn
    /// through, a person standing in it): the plan's point detour_ahead_m ahead is avoided by A*
    /// (a disc of detour_radius_m, lethal) for detour_memory_s, at most max_detours times per leg;
    /// with no other way, A* plans through it again. The first plan around each of the leg's first
    /// clocked_detours stuck spots restarts the give-up clock, progress measured along it (it is
    /// longer than the way that failed); later detours and a plan through a spot again do not.
    double detour_ahead_m = 0.6;
    double detour_radius_m = 0.35;
    double detour_memory_s = 30.0;
    int max_detours = 3;
    int clocked_detours = 2;
    double plan_to_tolerance =
        0.6;  ///< A* ends anywhere within this share of the leg's tolerance (0: at the point)
    std::vector<std::string> validate() const;         ///< everything, layers and planners included
    std::vector<std::string> validate_policy() const;  ///< the policy constants alone
};

struct SystemParams {
    /// The sensor on the robot's base (extrinsics): odometry poses the base, the points are the
    /// sensor's.
    Isometry3 T_base_sensor = Isometry3::Identity();
    /// The pose of every sweep: LiDAR odometry fused with the wheel odometry (the paper's front
    /// end); false: the wheel odometry alone.
    bool lidar_odometry_enabled = true;
    odometry::OdometryParams lidar_odometry;  ///< the `lidar_odometry` section
    KeyframeParams keyframe;
    bool verification_enabled =
        true;  ///< with a CAD library: 4-DoF ICP, p_exist as existence evidence
    verification::VerifyParams verify;
    /// Without CAD models (no verification): chairs turned to their backs' yaw before the map.
    verification::BackYawParams back_yaw;
    TrackedShapeParams shapes;  ///< with a shape prior: learned shapes kept per tracked object
    tracking::TrackerParams tracker;
    NavigatorParams navigator;
    /// Every problem, prefixed by its section ("tracker.min_hits must be >= 1").
    std::vector<std::string> validate() const;
};

/// The robot into every stage that must know it, in one place: the costmap's inflation (inscribed
/// and circumscribed radii) and what its obstacle layer marks (the body's heights), DWA's footprint
/// and limits (its top speed at most the robot's), the collision monitor's footprint, body, limits
/// and sensor height, and the extrinsics. `T_base_sensor`: measured extrinsics (null: the
/// description's, lidar_height_m above the base's centre).
void apply_robot(const RobotDescription& robot, SystemParams& params,
                 const Isometry3* T_base_sensor = nullptr);

}  // namespace makeway::pipeline
