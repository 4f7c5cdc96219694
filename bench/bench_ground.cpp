// RANSAC ground plane on one keyframe (5 VLP-32C sweeps, the study space's start pose), hypotheses
// scored by inlier area (one point per 10 cm voxel, the default) or by inlier points.
#include <benchmark/benchmark.h>

#include "makeway/perception/ground.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/world.hpp"

namespace {

using namespace makeway;

const PointCloud& study_space_keyframe() {
    static const PointCloud keyframe = [] {
        const sim::Scene scene = sim::generate_scene({.layout = sim::Layout::kStudySpace});
        sim::World world(scene, sim::models_of(scene));
        const Isometry3 T_world_sensor =
            lift_to_3d(scene.start) * sim::RobotParams{}.T_robot_sensor();
        PointCloud c;
        for (int k = 0; k < 5; ++k)
            c.append(sim::simulate_sweep(
                world, {}, [&](double) { return T_world_sensor; }, 0.1 * k, 0, k));
        return c;
    }();
    return keyframe;
}

void BM_GroundPlane(benchmark::State& state) {
    const PointCloud& keyframe = study_space_keyframe();
    perception::GroundPlaneParams params;
    params.voxel_m = static_cast<double>(state.range(0)) / 100.0;
    for (auto _ : state) benchmark::DoNotOptimize(perception::fit_ground_plane(keyframe, params));
    state.counters["points"] = static_cast<double>(keyframe.size());
}
BENCHMARK(BM_GroundPlane)->Arg(10)->Arg(0)->ArgName("voxel_cm")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
