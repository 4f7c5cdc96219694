#include "makeway/pipeline/system_params.hpp"

#include <algorithm>
#include <stdexcept>

#include "makeway/perception/accumulator.hpp"

namespace makeway::pipeline {
namespace {

void add(std::vector<std::string>& out, const std::string& prefix, const std::vector<std::string>& problems) {
    for (const std::string& p : problems) out.push_back(prefix + "." + p);
}

}  // namespace

void throw_if_problems(const std::vector<std::string>& problems) {
    if (problems.empty()) return;
    std::string all;
    for (const std::string& p : problems) all += (all.empty() ? "" : "; ") + p;
    throw std::invalid_argument(all);
}

void apply_robot(const RobotDescription& robot, SystemParams& params, const Isometry3* T_base_sensor) {
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
    m.sensor_height_m = params.T_base_sensor.translation().z();  // the blind ring is the mounted sensor's
}

std::vector<std::string> KeyframeParams::validate() const {
    std::vector<std::string> p;
    p = perception::AccumulatorParams{.window = window, .deskew = deskew}.validate();
    if (every < 1 || every > 1000) p.push_back("every must be in [1, 1000]");
    add(p, "ground", ground.validate());
    add(p, "ground_filter", ground_filter.validate());
    return p;
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

std::vector<std::string> NavigatorParams::validate_policy() const {
    std::vector<std::string> p;
    auto positive = [&](double v, const char* name, double hi) {
        if (!(v > 0.0 && v <= hi)) p.push_back(std::string(name) + " must be in (0, " + std::to_string(static_cast<int>(hi)) + "]");
    };
    positive(replan_period_s, "replan_period_s", 600);
    positive(blocked_lookahead_m, "blocked_lookahead_m", 100);
    if (!(blocked_ignore_m >= 0.0 && blocked_ignore_m < blocked_lookahead_m)) p.push_back("blocked_ignore_m must be in [0, blocked_lookahead_m)");
    if (turn_target_index < 1 || turn_target_index > 1000) p.push_back("turn_target_index must be in [1, 1000]");
    positive(turn_rate_radps, "turn_rate_radps", 10);
    positive(stuck_progress_m, "stuck_progress_m", 10);
    positive(stuck_timeout_s, "stuck_timeout_s", 600);
    positive(backup_speed_mps, "backup_speed_mps", 5);
    positive(backup_duration_s, "backup_duration_s", 60);
    positive(standstill_timeout_s, "standstill_timeout_s", 600);
    positive(standstill_v_mps, "standstill_v_mps", 1);
    positive(standstill_w_radps, "standstill_w_radps", 1);
    positive(waypoint_tolerance_m, "waypoint_tolerance_m", 10);
    positive(goal_tolerance_m, "goal_tolerance_m", 10);
    positive(give_up_s, "give_up_s", 3600);
    if (!(plan_to_tolerance >= 0.0 && plan_to_tolerance < 1.0)) p.push_back("plan_to_tolerance must be in [0, 1)");
    if (!(detour_ahead_m >= 0.0 && detour_ahead_m <= 10.0)) p.push_back("detour_ahead_m must be in [0, 10]");
    if (!(detour_radius_m >= 0.0 && detour_radius_m <= 5.0)) p.push_back("detour_radius_m must be in [0, 5] (0: no detours)");
    if (!(detour_memory_s >= 0.0 && detour_memory_s <= 3600.0)) p.push_back("detour_memory_s must be in [0, 3600]");
    if (max_detours < 0 || max_detours > 100) p.push_back("max_detours must be in [0, 100] (0: no detours)");
    return p;
}

std::vector<std::string> SystemParams::validate() const {
    std::vector<std::string> p;
    if (!T_base_sensor.matrix().allFinite()) p.push_back("T_base_sensor must be finite");
    if (lidar_odometry) add(p, "lidar_odometry", odometry.validate());
    add(p, "keyframe", keyframe.validate());
    add(p, "verification", verify.validate());
    add(p, "verification.shapes", shapes.validate());
    add(p, "tracking", tracker.validate());
    add(p, "navigation", navigator.validate());
    return p;
}

}  // namespace makeway::pipeline
