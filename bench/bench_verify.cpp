// Verification costs on one core: sampling and indexing a CAD model (once per model, at start-up),
// and verifying one flipped chair detection against a 4-model chair library, with the lookup grids
// (the default) and with exact k-d tree searches only.
#include <benchmark/benchmark.h>

#include "makeway/common/angles.hpp"
#include "makeway/eval/verify_bench.hpp"
#include "makeway/sim/furniture.hpp"

namespace {

using namespace makeway;

verification::CadLibrary chair_library(const verification::CadLibraryParams& params) {
    verification::CadLibrary lib(params);
    for (sim::FurnitureStyle s : sim::styles_of(ObjectClass::kChair)) {
        lib.add(std::string(sim::to_string(s)), ObjectClass::kChair,
                sim::make_furniture(s, 3).mesh_object);
    }
    return lib;
}

void BM_CadLibraryAdd(benchmark::State& state) {
    const auto style = static_cast<sim::FurnitureStyle>(state.range(0));
    const TriangleMesh mesh = sim::make_furniture(style, 3).mesh_object;
    std::size_t bytes = 0;
    for (auto _ : state) {
        verification::CadLibrary lib;
        lib.add("model", sim::class_of(style), mesh);
        bytes = 0;
        for (const auto& level : lib.models().front().levels) {
            bytes += level.points_object.size() * 2 * sizeof(Eigen::Vector3d) +
                     (level.grid ? level.grid->memory_bytes() : 0);
        }
        benchmark::DoNotOptimize(lib);
    }
    state.SetLabel(std::string(sim::to_string(style)));
    state.counters["MB"] = static_cast<double>(bytes) / 1e6;
}
BENCHMARK(BM_CadLibraryAdd)
    ->DenseRange(0, sim::kNumFurnitureStyles - 1)
    ->Unit(benchmark::kMillisecond);

void BM_VerifyFlippedChair(benchmark::State& state) {
    const eval::BenchKeyframe kf = eval::simulate_bench_keyframe(0, 0);
    verification::CadLibraryParams params;
    if (state.range(0) == 0) params.lookup_margin_m.clear();
    const verification::CadLibrary lib = chair_library(params);
    // Every chair of the scene, flipped by pi.
    std::vector<Detection> dets;
    for (std::size_t i = 0; i < kf.scene.objects.size(); ++i) {
        if (kf.scene.objects[i].cls != ObjectClass::kChair) continue;
        Detection d;
        d.cls = ObjectClass::kChair;
        d.box_sensor = kf.models[i].box_object.transformed(kf.T_world_sensor.inverse() *
                                                           lift_to_3d(kf.scene.objects[i].pose));
        d.box_sensor.yaw_rad = wrap_angle(d.box_sensor.yaw_rad + kPi);
        dets.push_back(d);
    }
    std::size_t i = 0;
    for (auto _ : state) {
        const Detection& d = dets[i++ % dets.size()];
        benchmark::DoNotOptimize(verification::verify_detection(
            kf.cloud_sensor, d, lib, {}, kf.floor_z_m(d.box_sensor.centre_m)));
    }
    state.SetLabel(state.range(0) ? "lookup grids" : "k-d tree only");
}
BENCHMARK(BM_VerifyFlippedChair)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
