// Rotated 3D IoU / GIoU per box pair: the tracker evaluates one per (detection, track) pair.
#include <benchmark/benchmark.h>

#include <vector>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"

namespace {

using namespace makeway;

std::vector<std::pair<OrientedBox, OrientedBox>> random_pairs(std::size_t n) {
    Rng rng = make_rng(5);
    std::vector<std::pair<OrientedBox, OrientedBox>> pairs;
    for (std::size_t i = 0; i < n; ++i) {
        auto box = [&] {
            return OrientedBox{
                {uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), 0.4},
                {uniform(rng, 0.4, 1.6), uniform(rng, 0.4, 1.0), uniform(rng, 0.7, 1.0)},
                uniform(rng, -kPi, kPi)};
        };
        pairs.emplace_back(box(), box());
    }
    return pairs;
}

void BM_BoxOverlap3d(benchmark::State& state) {
    const auto pairs = random_pairs(1024);
    std::size_t i = 0;
    for (auto _ : state) {
        const auto& [a, b] = pairs[i++ & 1023];
        benchmark::DoNotOptimize(box_overlap_3d(a, b));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_BoxOverlap3d);

void BM_IouBev(benchmark::State& state) {
    const auto pairs = random_pairs(1024);
    std::size_t i = 0;
    for (auto _ : state) {
        const auto& [a, b] = pairs[i++ & 1023];
        benchmark::DoNotOptimize(iou_bev(a, b));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_IouBev);

}  // namespace

BENCHMARK_MAIN();
