#include "makeway/eval/navigation.hpp"

#include <chrono>
#include <cmath>
#include <functional>

#include "makeway/common/angles.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/static_layer.hpp"
#include "makeway/eval/odometry_bench.hpp"
#include "makeway/eval/unavoidable_risk.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::eval {
namespace {

// The prebuilt map of walls: walls, pillars, and the parts of environment meshes the body can hit.
Costmap structure_grid(const sim::Scene& scene, double resolution, const BodyHeights& body) {
    const Eigen::Vector2d extent = scene.floor_max_m - scene.floor_min_m;
    Costmap g(scene.floor_min_m, resolution, static_cast<int>(std::ceil(extent.x() / resolution)),
              static_cast<int>(std::ceil(extent.y() / resolution)));
    for (const sim::Wall& w : scene.walls) {
        const Eigen::Vector2d d = w.b_m - w.a_m;
        costmap::fill_rectangle(g, 0.5 * (w.a_m + w.b_m), {d.norm() + w.thickness_m, w.thickness_m},
                                std::atan2(d.y(), d.x()), cost::kLethal);
    }
    for (const sim::Pillar& p : scene.pillars)
        costmap::fill_rectangle(g, p.centre_m, p.size_m, 0.0, cost::kLethal);
    for (const sim::EnvironmentMesh& e : scene.environment) {
        if (!e.mesh_world) continue;
        for (const Eigen::Vector2d& q : sim::low_surface_points(*e.mesh_world, body, resolution)) {
            const Eigen::Vector2i c = g.cell_of(q);
            if (g.inside(c.x(), c.y())) g.at(c.x(), c.y()) = cost::kLethal;
        }
    }
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

// One sweep as the simulator made it: what a robot receives, and the truth the baselines get.
struct SimSweep {
    const PointCloud* points_sensor = nullptr;
    double stamp_s = 0.0, duration_s = 0.1;
    Pose2 odometry_start, odometry_end;                  // wheel odometry (drifting)
    Isometry3 T_world_sensor_start, T_world_sensor_end;  // truth
    double v_mps = 0.0, w_radps = 0.0;                   // truth, at the sweep's end
};

// What the robot's software makes of a sweep: where it believes it is, and the guarded command
// (the navigator, then the collision monitor: pipeline::Controller, for every method).
struct Thought {
    Pose2 pose;
    pipeline::Controller::Step control;
};
using Think = std::function<Thought(const SimSweep&)>;

// Scores one physics step against the truth.
struct Scorer {
    const sim::Scene& scene;
    const std::vector<sim::ObjectModel>& models;
    const sim::CollisionChecker& checker;
    const NavParams& params;
    NavRunResult& out;
    sim::ContactJudge judge;
    bool in_collision = false, touching_person = false;
    std::vector<bool> near_chair;

    void step(const sim::RobotState& state, double ts, double dt) {
        using Against = sim::CollisionChecker::Against;
        const Pose2& pose = state.pose;
        const bool colliding = checker.collides(pose, ts, Against::kStructureAndFurniture);
        out.collisions += colliding && !in_collision;
        in_collision = colliding;
        const bool person = !scene.walkers.empty() && checker.collides(pose, ts, Against::kPeople);
        out.person_contacts += person && !touching_person;
        touching_person = person;
        // Each contact, when it starts, is the robot's or another's doing.
        for (ContactEvent& e : judge.step(state, ts, colliding || person)) {
            ContactCounts& counts = e.kind == "walls"       ? out.wall_contacts
                                    : e.kind == "furniture" ? out.furniture_contacts
                                                            : out.people_contacts;
            ++(e.robot_caused ? counts.robot_caused : counts.other_caused);
            out.contact_events.push_back(std::move(e));
        }
        const Eigen::Vector2d c(pose.x_m, pose.y_m);
        const auto truth = ground_truth_objects(scene, models, ts);
        bool risky = false;
        near_chair.resize(truth.size(), false);
        for (std::size_t j = 0; j < truth.size(); ++j) {
            risky |= costmap::in_affordance_zone(truth[j], params.scored_zones(),
                                                 c);  // the same zones for every method
            const bool moving = truth[j].velocity_mps.norm() > 0.02;
            const bool near = moving && distance_to_box(truth[j].box_world, c) <
                                            params.robot.inscribed_radius_m() + params.near_miss_m;
            out.near_misses += near && !near_chair[j] && !colliding;
            near_chair[j] = near;
        }
        if (risky) out.risk_time_s += dt;
    }
};

pipeline::NavigatorParams navigator_params(const NavMethod& method, const NavParams& params) {
    pipeline::NavigatorParams n = params.system.navigator;
    n.inflation.inflation_radius_m = method.inflation_radius_m;
    n.inflation.inscribed_radius_m *= method.inscribed_scale;
    n.affordance_layer = method.affordance;
    n.obstacle.threads = 1;  // runs go in parallel instead (shards, --threads)
    return n;
}

// The scene's legs: the waypoint, then the goal.
std::vector<Eigen::Vector2d> route_of(const sim::Scene& scene) {
    return {{scene.waypoint.x_m, scene.waypoint.y_m}, {scene.goal.x_m, scene.goal.y_m}};
}

// The simulator's loop: act on the last command while the LiDAR sweeps (the robot moves within
// the sweep), score every physics step, then let the robot's software see the sweep and decide.
// Intensity is simulated only when the software reads it (`reads_intensity`).
NavRunResult drive(const sim::Scene& scene, const NavMethod& method, const NavParams& params,
                   const pipeline::Controller& controller, bool reads_intensity,
                   const Think& think) {
    NavRunResult out;
    out.method = method.name;
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    const sim::CollisionChecker checker(scene, models, params.robot);
    if (auto shortest =
            sim::mission_route(scene, sim::make_nav_grid(scene, checker, params.robot))) {
        out.shortest_m = sim::route_length_m(*shortest);
    }
    {
        const pipeline::NavigatorParams& n = params.system.navigator;
        const UnavoidableRisk u = unavoidable_risk(
            scene, checker, ground_truth_objects(scene, models, 0.0), params.robot,
            params.scored_zones(), n.waypoint_tolerance_m, n.goal_tolerance_m, params.resolution_m);
        out.unavoidable_risk_s = u.reachable ? u.risk_time_s : -1.0;
    }
    sim::World world(scene, models);
    sim::WheelOdometry odometry(scene.start, params.odometry, params.seed ^ 0x0D0ULL);
    Scorer scorer{scene,   models,
                  checker, params,
                  out,     sim::ContactJudge(checker, params.robot, params.robot_caused_speed_mps)};
    sim::RobotState state;
    state.pose = scene.start;
    VelocityCommand cmd;
    const double period = 1.0 / params.lidar.rate_hz, dt = period / params.physics_steps;
    const Isometry3 T_robot_sensor = params.robot.T_robot_sensor();
    sim::LidarParams lidar = params.lidar;
    lidar.intensity = lidar.intensity && reads_intensity;
    out.min_clearance_m = 1e9;
    for (int k = 0; k * period < params.time_limit_s; ++k) {
        if (params.on_sweep) params.on_sweep();
        const double t = k * period;
        out.trajectory.push_back(state.pose);
        // Act for one sweep period, scoring each physics step; keep the poses for the sweep.
        std::vector<Pose2> poses{state.pose};
        const Pose2 odometry_start = odometry.pose();
        const double risk_before = out.risk_time_s;
        for (int i = 0; i < params.physics_steps; ++i) {
            const Pose2 before = state.pose;
            state = sim::step_diff_drive(state, cmd, dt, params.robot);
            odometry.update(before, state.pose);
            out.distance_m += std::hypot(state.pose.x_m - before.x_m, state.pose.y_m - before.y_m);
            poses.push_back(state.pose);
            scorer.step(state, t + (i + 1) * dt, dt);
        }
        out.cycle_risk_s.push_back(out.risk_time_s - risk_before);
        out.min_clearance_m =
            std::min(out.min_clearance_m, checker.clearance_m(state.pose, t + period, 2.0));
        // Sense: the sweep over that period, from the moving sensor.
        const sim::PoseAtTime T_world_sensor_at =
            sim::sensor_pose_along(std::move(poses), t, dt, T_robot_sensor);
        const PointCloud sweep = sim::simulate_sweep(world, lidar, T_world_sensor_at, t,
                                                     params.seed, static_cast<std::uint64_t>(k));
        const Thought thought =
            think({&sweep, t, period, odometry_start, odometry.pose(), T_world_sensor_at(t),
                   T_world_sensor_at(t + period), state.v_mps, state.w_radps});
        out.estimated_trajectory.push_back(thought.pose);
        const pipeline::Controller::Step& step = thought.control;
        out.replans += step.nav.replanned;
        out.recoveries += step.nav.started_recovery;
        if (step.nav.arrived) {
            out.time_s = t + period;
            break;
        }
        if (step.nav.gave_up) {
            out.time_s = t + period;
            out.gave_up = true;
            break;
        }
        out.monitor_ms_max = std::max(out.monitor_ms_max, step.monitor_ms);
        out.monitor_actions.push_back(step.guard.action);
        out.nav_states.emplace_back(pipeline::to_string_state(step.nav));
        out.commands.push_back(step.command);
        out.recoveries += step.guard.started_recovery;
        out.cycle_ms.push_back(step.nav.update_ms + step.monitor_ms);
        cmd = step.command;
    }
    out.trajectory.push_back(state.pose);
    const Pose2 believed =
        out.estimated_trajectory.empty() ? state.pose : out.estimated_trajectory.back();
    out.final_pose_error_m =
        std::hypot(believed.x_m - state.pose.x_m, believed.y_m - state.pose.y_m);
    // The belief of sweep k is the pose at its end: the true pose k + 1.
    out.pose_ate_m = trajectory_metrics(out.estimated_trajectory,
                                        {out.trajectory.begin() + 1, out.trajectory.end()})
                         .ate_rmse_m;
    const double to_goal =
        std::hypot(state.pose.x_m - scene.goal.x_m, state.pose.y_m - scene.goal.y_m);
    out.stop_distance_m = to_goal;
    const pipeline::Navigator& navigator = controller.navigator();
    out.reached_goal = navigator.arrived() && to_goal < params.arrival_radius_m;
    if (out.gave_up) {
        out.failure = "gave up (no plan or no progress for " +
                      std::to_string(static_cast<int>(params.system.navigator.give_up_s)) + " s)";
    } else if (!navigator.arrived()) {
        out.time_s = params.time_limit_s;
        out.failure = "time limit";
    } else if (!out.reached_goal) {
        out.failure =
            "stopped " + std::to_string(to_goal).substr(0, 4) + " m from the goal (pose estimate)";
    } else if (out.collisions > 0) {
        out.failure = "collision";
    }
    out.success = out.reached_goal && out.collisions == 0;
    out.spl = out.success && out.shortest_m > 0
                  ? out.shortest_m / std::max(out.distance_m, out.shortest_m)
                  : 0.0;
    out.final_costmap = navigator.costmap();
    out.last_plan = navigator.plan();
    return out;
}

}  // namespace

const std::vector<std::string>& nav_method_names() {
    static const std::vector<std::string> kNames{"con", "oppo", "gt-perc"};
    return kNames;
}

std::optional<NavMethod> nav_method(std::string_view name, const sim::RobotParams& robot) {
    const double r = robot.circumscribed_radius_m();
    if (name == "con") return NavMethod{"con", 3.0 * r, 3.0, false, false};
    if (name == "oppo") return NavMethod{"oppo", r, 1.0, false, false};
    if (name == "gt-perc") return NavMethod{"gt-perc", r, 1.0, true, false};
    if (name == "ours")
        return NavMethod{"ours", r, 1.0, true, true};  // gt-perc's planner on the online system
    return std::nullopt;
}

NavRunResult run_navigation(const sim::Scene& scene, const NavMethod& method, ObjectSource& source,
                            const NavParams& params) {
    const Isometry3 T_sensor_robot = params.robot.T_robot_sensor().inverse();
    pipeline::NavigatorParams navigator = navigator_params(method, params);
    navigator.monitor.give_way_lag_s = 0.0;  // the truth's boxes are where the chairs are now
    pipeline::Controller controller(
        params.static_map ? *params.static_map
                          : structure_grid(scene, params.resolution_m, params.robot.body()),
        navigator);
    controller.set_route(route_of(scene));
    return drive(
        scene, method, params, controller, source.reads_intensity(), [&](const SimSweep& s) {
            // The baselines are fed the truth: the pose, the velocity and (gt-perc) the objects.
            Thought th;
            th.pose = project_to_plane(s.T_world_sensor_end * T_sensor_robot);
            const PointCloud points_world =
                perception::deskew_to_world({*s.points_sensor, s.stamp_s, s.duration_s,
                                             s.T_world_sensor_start, s.T_world_sensor_end});
            th.control = controller.step({s.stamp_s + s.duration_s, th.pose, s.v_mps, s.w_radps,
                                          &points_world, s.T_world_sensor_end.translation(),
                                          source.objects({s.stamp_s + s.duration_s,
                                                          s.T_world_sensor_end, s.points_sensor})});
            return th;
        });
}

pipeline::OnlineSystemSetup online_system_setup(const sim::Scene& scene, const NavMethod& method,
                                                const NavParams& params) {
    // What a robot has: its start pose, its sweeps and its wheel odometry, the prebuilt map of
    // walls (objects stand in its free space). Nothing else passes.
    pipeline::OnlineSystemSetup setup;
    setup.params = params.system;
    setup.params.navigator = navigator_params(method, params);
    setup.params.lidar_odometry.threads = 1;  // runs go in parallel instead (shards, --threads)
    setup.start = scene.start;
    setup.map = params.static_map ? *params.static_map
                                  : structure_grid(scene, params.resolution_m, params.robot.body());
    setup.map_kind = pipeline::MapKind::kWalls;
    return setup;
}

NavRunResult run_navigation_online(const sim::Scene& scene, const NavMethod& method,
                                   const perception::ObjectDetector& detector,
                                   const verification::CadLibrary* library, const NavParams& params,
                                   const verification::ShapePrior* prior) {
    pipeline::OnlineSystemSetup setup = online_system_setup(scene, method, params);
    setup.detector = &detector;
    setup.library = library;
    setup.prior = prior;
    pipeline::OnlineSystem online(setup);
    online.set_route(route_of(scene));
    std::vector<KeyframeObjects> keyframes;
    std::vector<pipeline::StageTiming> timing;
    NavRunResult out =
        drive(scene, method, params, online.controller(), detector.uses_intensity(),
              [&](const SimSweep& s) {
                  // Only the channels a sensor gives are copied (the simulator's labels stay here).
                  const pipeline::OnlineStep step =
                      online.process({pipeline::sensor_channels_only(*s.points_sensor), s.stamp_s,
                                      s.duration_s, s.odometry_start, s.odometry_end});
                  const pipeline::SweepResult& r = step.sweep;
                  if (r.keyframe) {
                      keyframes.push_back({r.keyframe->stamp_s, r.keyframe->T_world_keyframe,
                                           r.keyframe->detections.size(),
                                           r.keyframe->evidence.size(), r.objects});
                      timing.push_back(r.timing);
                  }
                  return Thought{r.pose, step.control};
              });
    out.keyframes = std::move(keyframes);
    out.keyframe_timing = std::move(timing);
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    for (const KeyframeObjects& k : out.keyframes)
        out.map_sanity.add(check_map(k.objects, scene, models, k.stamp_s));
    return out;
}

}  // namespace makeway::eval
