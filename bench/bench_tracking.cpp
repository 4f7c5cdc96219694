// Object map updates on one core with N objects per frame (detections with noise, 20 % missed,
// 10 % false positives), and the Hungarian assignment alone.
#include <benchmark/benchmark.h>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/tracking/hungarian.hpp"
#include "makeway/tracking/object_map.hpp"

namespace {

using namespace makeway;

void BM_ObjectMapUpdate(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    Rng rng = make_rng(1);
    std::vector<OrientedBox> objects;
    for (int i = 0; i < n; ++i) {
        objects.push_back({{uniform(rng, -8, 8), uniform(rng, -8, 8), 0.45},
                           {0.5, 0.5, 0.9},
                           uniform(rng, -kPi, kPi)});
    }
    tracking::ObjectMap map;
    double t = 0;
    for (auto _ : state) {
        std::vector<Detection> dets;
        for (const OrientedBox& o : objects) {
            if (uniform(rng, 0, 1) < 0.2) continue;
            Detection d;
            d.box_sensor = o;
            d.box_sensor.centre_m +=
                Eigen::Vector3d(normal(rng, 0, 0.05), normal(rng, 0, 0.05), 0.0);
            dets.push_back(d);
        }
        for (int i = 0; i < n / 10; ++i) {
            Detection d;
            d.box_sensor = {{uniform(rng, -8, 8), uniform(rng, -8, 8), 0.45}, {0.5, 0.5, 0.9}, 0.0};
            d.score = 0.5;
            dets.push_back(d);
        }
        benchmark::DoNotOptimize(map.update(dets, Isometry3::Identity(), t));
        t += 0.1;
    }
    state.counters["fps"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ObjectMapUpdate)->Arg(10)->Arg(30)->Arg(60)->Unit(benchmark::kMicrosecond);

void BM_Hungarian(benchmark::State& state) {
    const auto n = static_cast<Eigen::Index>(state.range(0));
    Rng rng = make_rng(2);
    Eigen::MatrixXd c(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j) c(i, j) = uniform(rng, 0, 1);
    }
    for (auto _ : state) benchmark::DoNotOptimize(tracking::min_cost_assignment(c));
}
BENCHMARK(BM_Hungarian)->Arg(30)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
