// The online system's per-sweep work on one core (the target: at most 10 ms median per
// sweep): LiDAR odometry against its local map, the sweep de-skewed into the world, and the
// object-aware costmap's update (obstacle raytracing, affordance zones, inflation), over a 50-sweep
// drive through a medium scene with a walker and pulled chairs. The keyframe chain (detector,
// verification, tracking) is timed by `makeway run`'s summary.json.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "makeway/odometry/lidar_odometry.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/pipeline/navigator.hpp"
#include "makeway/pipeline/object_costmap.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"
#include "makeway/verification/part_outlines.hpp"

namespace {

using namespace makeway;

struct Drive {
    std::vector<sim::SimFrame> frames;
    Pose2 start;
    std::vector<ObjectEstimate> objects;  // the truth, as the affordance layer's input
    Costmap free_map;
    Eigen::Vector2d goal = Eigen::Vector2d::Zero();  // the scene's goal
    std::vector<PointCloud> worlds;  // each sweep de-skewed on the true poses, world frame
    std::vector<Polygon2> parts;     // every object's body-height parts at its true pose
};

const Drive& medium_drive() {
    static const Drive drive = [] {
        sim::SceneGenParams g;
        g.seed = 11;
        g.density = sim::Density::kMedium;
        const sim::Scene scene = sim::generate_scene(g);
        const sim::RobotParams robot;
        const auto route = sim::drive_route(
            scene, sim::CollisionChecker(scene, sim::models_of(scene), robot), robot);
        sim::SequenceSimulator sim(scene, route.value_or(std::vector<Eigen::Vector2d>{}), {});
        Drive d;
        d.start = sim.start_pose();
        for (int k = 0; k < 50; ++k) d.frames.push_back(sim.next());
        const std::vector<sim::ObjectModel> models = sim::models_of(scene);
        for (std::size_t i = 0; i < models.size(); ++i) {
            verification::CadLibrary one;
            one.add("m", ObjectClass::kChair, models[i].mesh_object);
            const Isometry3 T = d.frames.front().objects[i].T_world_object;
            for (const Polygon2& part : verification::part_outlines(
                     one.models().front().levels.back().points_object, robot.body())) {
                Polygon2 world;
                for (const Eigen::Vector2d& q : part)
                    world.push_back((T * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>());
                d.parts.push_back(std::move(world));
            }
        }
        for (const sim::ObjectState& s : d.frames.front().objects) {
            ObjectEstimate o;
            o.id = s.id;
            o.cls = s.cls;
            o.box_world = s.box_world;
            d.objects.push_back(o);
        }
        d.free_map =
            Costmap(Eigen::Vector2d(d.start.x_m - 20.0, d.start.y_m - 20.0), 0.05, 800, 800);
        d.goal = {scene.goal.x_m, scene.goal.y_m};
        for (const sim::SimFrame& f : d.frames) {
            d.worlds.push_back(perception::deskew_sweep(
                {f.points_sensor, f.stamp_s, 0.1, f.T_world_sensor, f.T_world_sensor},
                Isometry3::Identity(), false));
        }
        return d;
    }();
    return drive;
}

// The navigator's defaults with the robot's inflation radii, affordance zones on or off.
pipeline::NavigatorParams navigator_params(const sim::RobotParams& robot, bool affordance) {
    pipeline::NavigatorParams p;
    p.affordance_layer = affordance;
    p.inflation.inscribed_radius_m = robot.inscribed_radius_m();
    p.inflation.inflation_radius_m = robot.circumscribed_radius_m();
    return p;
}

// Per sweep (issue 31's target: at most 8 ms median): the odometry, the de-skewing and the
// costmap's update, one benchmark iteration the 50-sweep drive; threads:1 on one core, threads:2
// with the odometry's correspondence search and the costmap's rays and distance transform on both
// cores (the same poses and costs).
void BM_PerSweep(benchmark::State& state) {
    const int threads = static_cast<int>(state.range(0));
    const tbb::global_control cores(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    const Drive& d = medium_drive();
    const sim::RobotParams robot;
    odometry::OdometryParams odometry_params;
    odometry_params.threads = threads;
    pipeline::NavigatorParams costmap_params = navigator_params(robot, true);
    costmap_params.obstacle.threads = threads;
    std::size_t sweeps = 0;
    for (auto _ : state) {
        state.PauseTiming();
        odometry::LidarOdometry odo(odometry_params, robot.T_robot_sensor(), d.start);
        pipeline::ObjectCostmap costmap(d.free_map, costmap_params);
        state.ResumeTiming();
        for (const sim::SimFrame& f : d.frames) {
            const auto r = odo.register_sweep(f.points_sensor, f.stamp_s, 0.1, f.odometry_pose,
                                              f.odometry_end_pose);
            const PointCloud world = perception::deskew_sweep(
                {f.points_sensor, f.stamp_s, 0.1, r.T_world_sensor_start, r.T_world_sensor_end},
                Isometry3::Identity(), true);
            costmap.update(&world, r.T_world_sensor_end.translation(), d.objects);
            ++sweeps;
        }
    }
    state.counters["sweeps_per_s"] =
        benchmark::Counter(static_cast<double>(sweeps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PerSweep)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The LiDAR odometry alone (the larger half of a sweep): de-skewing with the wheels' motion,
// registration against the local voxel map, the map's update; one benchmark iteration is the
// 50-sweep drive. Counters: Gauss-Newton iterations and source points per sweep.
void BM_Odometry(benchmark::State& state) {
    const Drive& d = medium_drive();
    const sim::RobotParams robot;
    double iterations = 0.0, source = 0.0, sweeps = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        odometry::LidarOdometry odo({}, robot.T_robot_sensor(), d.start);
        state.ResumeTiming();
        for (const sim::SimFrame& f : d.frames) {
            const auto r = odo.register_sweep(f.points_sensor, f.stamp_s, 0.1, f.odometry_pose,
                                              f.odometry_end_pose);
            iterations += r.iterations;
            source += static_cast<double>(r.source_points);
            sweeps += 1.0;
        }
    }
    state.counters["ms_per_sweep"] =
        benchmark::Counter(sweeps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["iterations"] = iterations / std::max(sweeps, 1.0);
    state.counters["source_points"] = source / std::max(sweeps, 1.0);
}
BENCHMARK(BM_Odometry)->Unit(benchmark::kMillisecond)->UseRealTime();

// The costmap's update alone (issue 31's target for it: the per-sweep total at most 8 ms median):
// obstacle marking and clearing from the de-skewed sweep, affordance zones of the scene's furniture
// (argument 1) or none, inflation; one benchmark iteration is one sweep of the 50-sweep drive.
void BM_CostmapUpdate(benchmark::State& state) {
    const Drive& d = medium_drive();
    const sim::RobotParams robot;
    const pipeline::NavigatorParams params = navigator_params(robot, state.range(0) != 0);
    pipeline::ObjectCostmap costmap(d.free_map, params);
    std::size_t k = 0;
    for (auto _ : state) {
        const sim::SimFrame& f = d.frames[k % d.frames.size()];
        costmap.update(&d.worlds[k % d.worlds.size()], f.T_world_sensor.translation(), d.objects);
        benchmark::DoNotOptimize(costmap.master().cost.data());
        ++k;
    }
}
BENCHMARK(BM_CostmapUpdate)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("affordance")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The control cycle of bench nav's methods (issue 18's target: at most 10 ms median on one core):
// Navigator::step = costmap update (obstacles, affordance zones, inflation) + A* when due + DWA
// inside the plan's envelope, on the same drive's de-skewed sweeps and true poses, toward the
// scene's goal; one benchmark iteration is one cycle.
void BM_ControlCycle(benchmark::State& state) {
    const tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
    const Drive& d = medium_drive();
    const sim::RobotParams robot;
    const std::vector<PointCloud>& worlds = d.worlds;
    const pipeline::NavigatorParams params = navigator_params(robot, state.range(0) != 0);
    pipeline::Navigator nav(d.free_map, params);
    nav.set_route({d.goal});
    std::size_t k = 0;
    for (auto _ : state) {
        const sim::SimFrame& f = d.frames[k % d.frames.size()];
        const auto step =
            nav.step({0.1 * static_cast<double>(k), f.true_pose, 0.5, 0.0,
                      &worlds[k % worlds.size()], f.T_world_sensor.translation(), d.objects});
        benchmark::DoNotOptimize(step.command);
        ++k;
    }
}
BENCHMARK(BM_ControlCycle)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("affordance")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The collision monitor's cycle (issue 29's target: at most 1 ms on one core): the sweep's
// returns the body can hit thinned into its 1 s memory, then the stop, approach and slowdown
// checks of a full-speed command along a gentle arc, on the same drive's de-skewed sweeps;
// bridge_gaps: 0 with narrow gaps left open, 1 closed (the default, bridge_gap_m); parts: 1 with
// every object's body-height parts handed in (object_parts: what the Controller gives when the map
// has placed each object by its CAD model), 0 none; walkers: 1 with every chair of the drive
// handed in as known and a return seen in only one of the last sweeps new away from them
// (dynamic_min_seen_off_chairs 2), 0 neither.
void BM_CollisionMonitor(benchmark::State& state) {
    const Drive& d = medium_drive();
    const sim::RobotParams robot;
    const std::vector<PointCloud>& worlds = d.worlds;
    planning::CollisionMonitorParams p;
    p.apply_robot(robot);  // its speeds and accelerations are the monitor's defaults too
    if (state.range(0) == 0) p.bridge_gap_m = 0.0;  // narrow gaps left open
    // give_way: a chair 0.2 m beside the robot pulled toward it every cycle (within the margin of
    // a standing robot in 1 s: the standing and the commanded motion weighed each cycle).
    if (state.range(2) != 0) p.give_way_horizon_s = 1.0;
    std::vector<Polygon2> chairs;
    if (state.range(3) != 0) {
        p.dynamic_min_seen_off_chairs = 2;
        for (const ObjectEstimate& o : d.objects) {
            if (o.cls == ObjectClass::kChair) chairs.push_back(pipeline::chair_footprint(o, 0.0));
        }
    }
    planning::CollisionMonitor monitor(p);
    std::size_t k = 0;
    for (auto _ : state) {
        const sim::SimFrame& f = d.frames[k % d.frames.size()];
        std::vector<planning::MovingOutline> movers;
        if (state.range(2) != 0) {
            const Isometry2 T = to_isometry(f.true_pose);
            const double y = 0.5 * robot.width_m + 0.2 + 0.225;
            movers.push_back(
                {{T * Eigen::Vector2d(-0.225, y - 0.225), T * Eigen::Vector2d(0.225, y - 0.225),
                  T * Eigen::Vector2d(0.225, y + 0.225), T * Eigen::Vector2d(-0.225, y + 0.225)},
                 T.linear() * Eigen::Vector2d(0.0, -0.17)});
        }
        const auto r = monitor.filter({0.1 * static_cast<double>(k),
                                       f.true_pose,
                                       &worlds[k % worlds.size()],
                                       {robot.max_v_mps, 0.3},
                                       robot.max_v_mps,
                                       0.3,
                                       state.range(1) != 0 ? &d.parts : nullptr,
                                       state.range(3) != 0 ? &chairs : nullptr,
                                       &movers});
        benchmark::DoNotOptimize(r.command);
        ++k;
    }
}
BENCHMARK(BM_CollisionMonitor)
    ->Args({0, 0, 0, 0})
    ->Args({1, 0, 0, 0})
    ->Args({1, 1, 0, 0})
    ->Args({1, 1, 1, 0})
    ->Args({1, 1, 1, 1})
    ->ArgNames({"bridge_gaps", "parts", "give_way", "walkers"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
