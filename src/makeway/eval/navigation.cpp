#include "makeway/eval/navigation.hpp"

#include <chrono>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/costmap/affordance_layer.hpp"
#include "makeway/costmap/layered_costmap.hpp"
#include "makeway/costmap/static_layer.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::eval {
namespace {

Costmap structure_grid(const sim::Scene& scene, double resolution) {
    const Eigen::Vector2d extent = scene.floor_max_m - scene.floor_min_m;
    Costmap g(scene.floor_min_m, resolution, static_cast<int>(std::ceil(extent.x() / resolution)),
              static_cast<int>(std::ceil(extent.y() / resolution)));
    for (const sim::Wall& w : scene.walls) {
        const Eigen::Vector2d d = w.b_m - w.a_m;
        costmap::fill_rectangle(g, 0.5 * (w.a_m + w.b_m), {d.norm() + w.thickness_m, w.thickness_m},
                                std::atan2(d.y(), d.x()), cost::kLethal);
    }
    for (const sim::Pillar& p : scene.pillars) costmap::fill_rectangle(g, p.centre_m, p.size_m, 0.0, cost::kLethal);
    return g;
}

// Distance from p to an oriented box's footprint [m] (0 inside).
double distance_to_box(const OrientedBox& box, const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - box.centre_m.head<2>();
    const double c = std::cos(box.yaw_rad), s = std::sin(box.yaw_rad);
    const Eigen::Vector2d q(std::abs(c * d.x() + s * d.y()) - 0.5 * box.size_m.x(),
                            std::abs(-s * d.x() + c * d.y()) - 0.5 * box.size_m.y());
    return q.cwiseMax(0.0).norm();
}

bool path_blocked(const Costmap& m, const std::vector<Eigen::Vector2d>& path, const Eigen::Vector2d& robot, double ahead_m) {
    double travelled = 0.0;
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < path.size(); ++i) {
        if ((path[i] - robot).squaredNorm() < (path[nearest] - robot).squaredNorm()) nearest = i;
    }
    for (std::size_t i = nearest; i < path.size() && travelled < ahead_m; ++i) {
        if (i > nearest) travelled += (path[i] - path[i - 1]).norm();
        const auto c = m.cost_at(path[i]);
        if (c && *c >= cost::kInscribed && *c != cost::kUnknown && (path[i] - robot).norm() > 0.3) return true;
    }
    return false;
}

}  // namespace

const std::vector<std::string>& nav_method_names() {
    static const std::vector<std::string> kNames{"con", "oppo", "gt-perc"};
    return kNames;
}

std::optional<NavMethod> nav_method(std::string_view name, const sim::RobotParams& robot) {
    const double r = robot.circumscribed_radius_m();
    if (name == "con") return NavMethod{"con", 3.0 * r, false};
    if (name == "oppo") return NavMethod{"oppo", r, false};
    if (name == "gt-perc") return NavMethod{"gt-perc", r, true};
    if (name == "ours") return NavMethod{"ours", r, true};  // gt-perc's planner, objects from the perception chain
    return std::nullopt;
}

NavRunResult run_navigation(const sim::Scene& scene, const NavMethod& method, ObjectSource& source,
                            const NavParams& params) {
    NavRunResult out;
    out.method = method.name;
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    const sim::CollisionChecker checker(scene, models, params.robot);
    if (auto shortest = sim::mission_route(scene, sim::make_nav_grid(scene, checker, params.robot))) {
        out.shortest_m = sim::route_length_m(*shortest);
    }
    sim::World world(scene, models);

    // The stack: static (the known building), obstacle (LiDAR), affordance (objects), inflation.
    const Costmap geometry = params.static_map ? *params.static_map : structure_grid(scene, params.resolution_m);
    costmap::LayeredCostmap layered(Costmap(geometry.origin_m, geometry.resolution_m, geometry.width, geometry.height));
    layered.add_layer(std::make_unique<costmap::StaticLayer>(geometry));
    layered.add_layer(std::make_unique<costmap::ObstacleLayer>(geometry, params.obstacle));
    if (method.affordance) layered.add_layer(std::make_unique<costmap::AffordanceLayer>(params.affordance));
    costmap::InflationParams inflation = params.inflation;
    inflation.inflation_radius_m = std::max(method.inflation_radius_m, inflation.inscribed_radius_m);
    layered.add_layer(std::make_unique<costmap::InflationLayer>(inflation));

    sim::RobotState state;
    state.pose = scene.start;
    const std::vector<Eigen::Vector2d> legs{{scene.waypoint.x_m, scene.waypoint.y_m}, {scene.goal.x_m, scene.goal.y_m}};
    std::size_t leg = 0;
    std::vector<Eigen::Vector2d> plan;
    double last_plan_t = -1e9;
    const costmap::AffordanceParams& risk_zones = params.affordance;  // the same zones for every method
    const double control_dt = 1.0 / params.lidar.rate_hz;
    const int physics_steps = 10;
    bool in_collision = false, touching_person = false;
    std::vector<bool> near_chair;
    Eigen::Vector2d progress_anchor(state.pose.x_m, state.pose.y_m);
    double progress_t = 0.0, recovery_until = -1.0;
    out.min_clearance_m = 1e9;
    const Isometry3 T_robot_sensor = params.robot.T_robot_sensor();

    double t = 0.0;
    for (int k = 0; t < params.time_limit_s; ++k, t = k * control_dt) {
        out.trajectory.push_back(state.pose);
        // Sense: one sweep from the current pose.
        const Isometry3 T_world_sensor = lift_to_3d(state.pose) * T_robot_sensor;
        const PointCloud sweep = sim::simulate_sweep(
            world, params.lidar, [&](double) { return T_world_sensor; }, t, params.seed, static_cast<std::uint64_t>(k));
        const PointCloud points_world = sweep.transformed(T_world_sensor);
        const auto objects = source.objects({t, T_world_sensor, &sweep});

        // Think: costmap update, global plan when due or blocked, DWA.
        const auto t0 = std::chrono::steady_clock::now();
        costmap::LayerInput input;
        input.points_world = &points_world;
        input.sensor_world_m = T_world_sensor.translation();
        input.objects = objects;
        layered.update(input);
        const Costmap& master = layered.master();
        const Eigen::Vector2d here(state.pose.x_m, state.pose.y_m);
        if (plan.empty() || t - last_plan_t >= params.replan_period_s || path_blocked(master, plan, here, 3.0)) {
            const planning::PlanResult p = planning::plan_astar(master, here, legs[leg], params.astar);
            if (p.status == planning::PlanStatus::kOk) plan = p.path_m;
            last_plan_t = t;
            ++out.replans;
        }
        VelocityCommand cmd;
        if (t < recovery_until) {
            cmd = {-0.15, 0.0};  // back up, then try again
        } else if (!plan.empty()) {
            planning::DwaParams dwa = params.dwa;
            dwa.max_v_mps = std::min(dwa.max_v_mps, params.robot.max_v_mps);
            const planning::DwaResult r = planning::dwa_step(master, {state.pose, state.v_mps, state.w_radps}, plan, dwa);
            if (r.found) {
                cmd = r.command;
            } else {  // every velocity collides: turn toward the path on the spot
                const Eigen::Vector2d target = plan.size() > 3 ? plan[3] : plan.back();
                cmd = {0.0, std::copysign(1.0, angle_diff(std::atan2(target.y() - here.y(), target.x() - here.x()),
                                                          state.pose.yaw_rad))};
            }
        }
        out.cycle_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

        // Act: the robot moves for one control period; score every physics step.
        const double dt = control_dt / physics_steps;
        for (int i = 0; i < physics_steps; ++i) {
            const double ts = t + (i + 1) * dt;
            const Pose2 before = state.pose;
            state = sim::step_diff_drive(state, cmd, dt, params.robot);
            out.distance_m += std::hypot(state.pose.x_m - before.x_m, state.pose.y_m - before.y_m);
            using Against = sim::CollisionChecker::Against;
            const bool colliding = checker.collides(state.pose, ts, Against::kStructureAndFurniture);
            out.collisions += colliding && !in_collision;
            in_collision = colliding;
            const bool person = !scene.walkers.empty() && checker.collides(state.pose, ts, Against::kPeople);
            out.person_contacts += person && !touching_person;
            touching_person = person;
            const Eigen::Vector2d c(state.pose.x_m, state.pose.y_m);
            const auto truth = ground_truth_objects(scene, models, ts);
            bool risky = false;
            near_chair.resize(truth.size(), false);
            for (std::size_t j = 0; j < truth.size(); ++j) {
                risky |= costmap::in_affordance_zone(truth[j], risk_zones, c);
                const bool moving = truth[j].velocity_mps.norm() > 0.02;
                const bool near = moving && distance_to_box(truth[j].box_world, c) < params.robot.inscribed_radius_m() + params.near_miss_m;
                out.near_misses += near && !near_chair[j] && !colliding;
                near_chair[j] = near;
            }
            if (risky) out.risk_time_s += dt;
        }
        out.min_clearance_m = std::min(out.min_clearance_m, checker.clearance_m(state.pose, t + control_dt, 2.0));

        // Legs: waypoint, then goal.
        const Eigen::Vector2d now(state.pose.x_m, state.pose.y_m);
        const double tol = leg == 0 ? params.waypoint_tolerance_m : params.goal_tolerance_m;
        if ((now - legs[leg]).norm() < tol) {
            if (leg + 1 == legs.size()) {
                out.reached_goal = true;
                out.time_s = t + control_dt;
                break;
            }
            ++leg;
            plan.clear();
        }
        // Stuck: little progress for 6 s -> back up for 1 s and replan.
        if ((now - progress_anchor).norm() > 0.3) {
            progress_anchor = now;
            progress_t = t;
        } else if (t - progress_t > 6.0 && t >= recovery_until) {
            recovery_until = t + 1.0;
            progress_t = t + 1.0;
            plan.clear();
            ++out.recoveries;
        }
    }
    out.trajectory.push_back(state.pose);
    if (!out.reached_goal) {
        out.time_s = params.time_limit_s;
        out.failure = "time limit";
    } else if (out.collisions > 0) {
        out.failure = "collision";
    }
    out.success = out.reached_goal && out.collisions == 0;
    out.spl = out.success && out.shortest_m > 0 ? out.shortest_m / std::max(out.distance_m, out.shortest_m) : 0.0;
    out.final_costmap = layered.master();
    out.last_plan = plan;
    return out;
}

}  // namespace makeway::eval
