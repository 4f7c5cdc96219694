// Point-cloud encode/decode throughput for one VLP-32C sweep (32 x 1800 points) and one 5-sweep
// keyframe, every channel present.
#include <benchmark/benchmark.h>

#include "io/kitti_bin.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "makeway/common/random.hpp"

namespace {

using namespace makeway;

PointCloud sweep(std::size_t n) {
    Rng rng = make_rng(1);
    PointCloud c;
    c.resize(n, PointFields::all());
    for (std::size_t i = 0; i < n; ++i) {
        c.xyz[i] = Eigen::Vector3f(static_cast<float>(normal(rng, 0, 8)),
                                   static_cast<float>(normal(rng, 0, 8)),
                                   static_cast<float>(uniform(rng, -0.4, 2.5)));
        c.intensity[i] = static_cast<float>(uniform(rng, 0, 100));
        c.ring[i] = static_cast<std::uint16_t>(i % 32);
        c.time_s[i] = static_cast<float>(i) * 1e-6f;
        c.label[i] = static_cast<std::uint8_t>(i % 8);
        c.instance[i] = static_cast<std::uint32_t>(i / 1000);
    }
    return c;
}

template <typename Encode, typename Decode>
void round_trip(benchmark::State& state, Encode encode, Decode decode, bool decode_only) {
    const PointCloud c = sweep(static_cast<std::size_t>(state.range(0)));
    const std::string bytes = encode(c);
    for (auto _ : state) {
        if (decode_only) {
            benchmark::DoNotOptimize(decode(bytes));
        } else {
            benchmark::DoNotOptimize(encode(c));
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
    state.counters["file_MB"] = static_cast<double>(bytes.size()) / 1e6;
}

#define MAKEWAY_CODEC_BENCH(NAME, ENCODE, DECODE)                                       \
    void BM_Write_##NAME(benchmark::State& s) { round_trip(s, ENCODE, DECODE, false); } \
    void BM_Read_##NAME(benchmark::State& s) { round_trip(s, ENCODE, DECODE, true); }   \
    BENCHMARK(BM_Write_##NAME)->Arg(57600)->Arg(288000)->Unit(benchmark::kMillisecond); \
    BENCHMARK(BM_Read_##NAME)->Arg(57600)->Arg(288000)->Unit(benchmark::kMillisecond)

auto pcd(io::PcdEncoding e) {
    return [e](const PointCloud& c) { return io::serialize_pcd(c, e); };
}
auto ply(io::PlyEncoding e) {
    return [e](const PointCloud& c) { return io::serialize_ply(c, e); };
}
const auto parse_pcd = [](const std::string& b) { return io::parse_pcd(b); };
const auto parse_ply = [](const std::string& b) { return io::parse_ply(b); };
const auto write_bin = [](const PointCloud& c) { return io::serialize_kitti_bin(c); };
const auto parse_bin = [](const std::string& b) { return io::parse_kitti_bin(b); };

MAKEWAY_CODEC_BENCH(PcdBinary, pcd(io::PcdEncoding::kBinary), parse_pcd);
MAKEWAY_CODEC_BENCH(PcdCompressed, pcd(io::PcdEncoding::kBinaryCompressed), parse_pcd);
MAKEWAY_CODEC_BENCH(PcdAscii, pcd(io::PcdEncoding::kAscii), parse_pcd);
MAKEWAY_CODEC_BENCH(PlyBinary, ply(io::PlyEncoding::kBinaryLittleEndian), parse_ply);
MAKEWAY_CODEC_BENCH(KittiBin, write_bin, parse_bin);

}  // namespace

BENCHMARK_MAIN();
