#include "makeway/pipeline/system_params.hpp"

#include <algorithm>
#include <stdexcept>

#include "makeway/perception/param_tables.hpp"
#include "makeway/pipeline/param_tables.hpp"

namespace makeway::pipeline {
namespace {

void add(std::vector<std::string>& out, const std::string& prefix,
         const std::vector<std::string>& problems) {
    for (const std::string& p : problems) out.push_back(prefix + "." + p);
}

}  // namespace

void apply_robot(const RobotDescription& robot, SystemParams& params,
                 const Isometry3* T_base_sensor) {
    params.T_base_sensor = T_base_sensor ? *T_base_sensor : robot.T_robot_sensor();
    NavigatorParams& n = params.navigator;
    n.inflation.inscribed_radius_m = robot.inscribed_radius_m();
    n.inflation.inflation_radius_m = robot.circumscribed_radius_m();
    n.obstacle.body = robot.body();  // what the robot can hit is what the costmap marks
    n.dwa.footprint_length_m = robot.length_m;
    n.dwa.footprint_width_m = robot.width_m;
    n.dwa.max_v_mps = std::min(n.dwa.max_v_mps, robot.max_v_mps);
    n.dwa.max_w_radps = robot.max_w_radps;
    n.dwa.acc_v_mps2 = robot.max_acc_mps2;
    n.dwa.acc_w_radps2 = robot.max_ang_acc_radps2;
    planning::CollisionMonitorParams& m = n.monitor;
    m.footprint_length_m = robot.length_m;
    m.footprint_width_m = robot.width_m;
    m.body = robot.body();
    m.max_v_mps = robot.max_v_mps;
    m.max_w_radps = robot.max_w_radps;
    m.max_acc_mps2 = robot.max_acc_mps2;
    m.max_ang_acc_radps2 = robot.max_ang_acc_radps2;
    m.sensor_height_m =
        params.T_base_sensor.translation().z();  // the blind ring is the mounted sensor's
}

const ParamTable<KeyframeParams>& keyframe_table() {
    using K = KeyframeParams;
    static const ParamTable<K> table = [] {
        ParamTable<K> t;
        t.add("keyframe_window", &K::window, closed(1, 100),
              "sweeps accumulated into a keyframe (de-skewed, newest sweep's frame)")
            .add("keyframe_every", &K::every, closed(1, 1000),
                 "sweeps between keyframes (10 Hz sweeps: 2 Hz keyframes)")
            .add("deskew", &K::deskew, "move each point with the sensor pose at its own time")
            .include(
                "ground_", [](K& k) -> perception::GroundPlaneParams& { return k.ground; },
                perception::ground_plane_table())
            .include(
                "", [](K& k) -> perception::GroundFilterParams& { return k.ground_filter; },
                perception::ground_filter_table());
        return t;
    }();
    return table;
}

std::vector<std::string> KeyframeParams::validate() const {
    return keyframe_table().problems(*this);
}

std::vector<std::string> NavigatorParams::validate() const {
    std::vector<std::string> p;
    add(p, "obstacle", obstacle.validate());
    add(p, "inflation", inflation.validate());
    add(p, "affordance", affordance.validate());
    add(p, "astar", astar.validate());
    add(p, "dwa", dwa.validate());
    add(p, "collision_monitor", monitor.validate());
    for (std::string& m : validate_policy()) p.push_back(std::move(m));
    return p;
}

const ParamTable<NavigatorParams>& navigator_policy_table() {
    using N = NavigatorParams;
    static const ParamTable<N> table = [] {
        ParamTable<N> t;
        t.add("replan_period_s", &N::replan_period_s, above(0.0, 600.0),
              "the global plan is renewed at least this often")
            .add("blocked_lookahead_m", &N::blocked_lookahead_m, above(0.0, 100.0),
                 "a lethal cell on the plan this far ahead forces a replan ...")
            .add("blocked_ignore_m", &N::blocked_ignore_m, closed(0.0, 100.0),
                 "... unless it is this close to the robot")
            .add("turn_target_index", &N::turn_target_index, closed(1, 1000),
                 "no safe velocity: turn on the spot toward this plan point")
            .add("turn_rate_radps", &N::turn_rate_radps, above(0.0, 10.0), "")
            .add("stuck_progress_m", &N::stuck_progress_m, above(0.0, 10.0),
                 "the way left along the plan shrinking by less than this ...")
            .add("stuck_timeout_s", &N::stuck_timeout_s, above(0.0, 600.0),
                 "... for this long: back up, then replan")
            .add("backup_speed_mps", &N::backup_speed_mps, above(0.0, 5.0), "")
            .add("backup_duration_s", &N::backup_duration_s, above(0.0, 60.0), "")
            .add("standstill_timeout_s", &N::standstill_timeout_s, above(0.0, 600.0),
                 "DWA's best velocity a standstill this long: stuck now (back up, replan around)")
            .add("standstill_v_mps", &N::standstill_v_mps, above(0.0, 1.0),
                 "standstill: slower than this ...")
            .add("standstill_w_radps", &N::standstill_w_radps, above(0.0, 1.0),
                 "... turning slower than this")
            .add("waypoint_tolerance_m", &N::waypoint_tolerance_m, above(0.0, 10.0),
                 "a waypoint counts as reached this close")
            .add("goal_tolerance_m", &N::goal_tolerance_m, above(0.0, 10.0),
                 "the goal counts as reached this close (own pose estimate)")
            .add(
                "give_up_s", &N::give_up_s, above(0.0, 3600.0),
                "no plan, or no progress along it despite recoveries, this long: the mission fails")
            .add("detour_ahead_m", &N::detour_ahead_m, closed(0.0, 10.0),
                 "stuck: A* avoids the plan's point this far ahead ...")
            .add("detour_radius_m", &N::detour_radius_m, closed(0.0, 5.0),
                 "... this wide (0: never) ...")
            .add("detour_memory_s", &N::detour_memory_s, closed(0.0, 3600.0), "... this long ...")
            .add("max_detours", &N::max_detours, closed(0, 100),
                 "... this often per leg (the first detour gets give_up_s of its own; no other "
                 "way: through it again)")
            .add("plan_to_tolerance", &N::plan_to_tolerance, below(0.0, 1.0),
                 "A* ends anywhere within this share of the tolerance (a goal inside a zone is "
                 "approached from its cheap side)")
            .require([](const N& n) { return n.blocked_ignore_m < n.blocked_lookahead_m; },
                     "blocked_ignore_m must be in [0, blocked_lookahead_m)");
        return t;
    }();
    return table;
}

std::vector<std::string> NavigatorParams::validate_policy() const {
    return navigator_policy_table().problems(*this);
}

std::vector<std::string> SystemParams::validate() const {
    std::vector<std::string> p;
    if (!T_base_sensor.matrix().allFinite()) p.push_back("T_base_sensor must be finite");
    if (lidar_odometry_enabled) add(p, "lidar_odometry", lidar_odometry.validate());
    add(p, "perception", keyframe.validate());  // its keys are the perception section's
    add(p, "verification", verify.validate());
    add(p, "verification.shapes", shapes.validate());
    add(p, "tracking", tracker.validate());
    add(p, "navigation", navigator.validate());
    return p;
}

}  // namespace makeway::pipeline
