// makeway bench sim: LiDAR simulation speed on a 20 x 20 m room with 40 pieces of furniture.
#include <algorithm>
#include <iostream>

#include "apps/command.hpp"
#include "io/json_io.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/lidar.hpp"

namespace makeway::apps {

struct BenchSimOptions {
    std::uint64_t seed = 0;
    int sweeps = 20;
    std::string out;  ///< optional JSON file
};

namespace {

sim::Scene bench_scene(std::uint64_t seed) {
    sim::Scene s;
    s.name = "bench_20x20_40_objects";
    s.floor_min_m = Eigen::Vector2d(-10.5, -10.5);
    s.floor_max_m = Eigen::Vector2d(10.5, 10.5);
    const double c = 10.0;
    s.walls = {{{-c, -c}, {c, -c}}, {{c, -c}, {c, c}}, {{c, c}, {-c, c}}, {{-c, c}, {-c, -c}}};
    Rng rng = make_rng(seed, 77);
    const int kSceneStyles =
        7;  // the styles generated scenes draw from (sim::scene_styles_of): comparable numbers
    std::vector<OrientedBox> boxes;
    while (s.objects.size() < 40) {
        sim::SceneObject o;
        o.id = static_cast<std::uint32_t>(s.objects.size() + 1);
        const auto style = static_cast<sim::FurnitureStyle>(uniform_int(rng, 0, kSceneStyles - 1));
        o.cls = sim::class_of(style);
        o.style = std::string(sim::to_string(style));
        o.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 20));
        o.pose = {uniform(rng, -8.5, 8.5), uniform(rng, -8.5, 8.5), uniform(rng, -kPi, kPi)};
        const OrientedBox box = sim::model_of(o).box_object.transformed(lift_to_3d(o.pose));
        if (std::hypot(o.pose.x_m, o.pose.y_m) < 1.5) continue;  // the sensor stands at the centre
        if (std::any_of(boxes.begin(), boxes.end(),
                        [&](const auto& b) { return iou_bev(b, box) > 0.0; }))
            continue;
        boxes.push_back(box);
        s.objects.push_back(o);
    }
    return s;
}

}  // namespace

int run_bench_sim(const BenchSimOptions& options) {
    const sim::Scene scene = bench_scene(options.seed);
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    sim::World world(scene, models);
    const sim::PoseAtTime pose = [](double t) {
        return make_T_xyz_yaw({0.5 * t, 0.0, 0.45}, 0.1 * t);
    };

    auto measure = [&](int threads, bool packets) {
        sim::LidarParams lidar;
        lidar.num_threads = threads;
        lidar.use_packets = packets;
        std::vector<double> ms;
        sim::SweepStats stats;
        for (int i = 0; i < options.sweeps + 1; ++i) {
            const auto t0 = SteadyClock::now();
            const PointCloud c =
                sim::simulate_sweep(world, lidar, pose, 0.1 * i, options.seed, i, &stats);
            const double dt = ms_since(t0);
            if (i > 0) ms.push_back(dt);  // the first sweep warms caches and builds the BVH
        }
        return std::make_pair(median(ms), stats);
    };
    const auto [ms_1t, stats] = measure(1, true);
    const auto [ms_2t, stats_2t] = measure(2, true);
    const auto [ms_1t_single, stats_single] = measure(1, false);
    const double rays = static_cast<double>(stats.rays);
    const io::Json j = {{"scene", scene.name},
                        {"triangles", world.num_triangles()},
                        {"rays_per_sweep", stats.rays},
                        {"returns_per_sweep", stats.returns},
                        {"sweeps", options.sweeps},
                        {"scan_ms", ms_1t},
                        {"scan_ms_2t", ms_2t},
                        {"rays_per_second_1t", rays / (ms_1t * 1e-3)},
                        {"rays_per_second_2t", rays / (ms_2t * 1e-3)},
                        {"rays_per_second_1t_single_rays", rays / (ms_1t_single * 1e-3)}};
    std::cout << io::dump_json(j, 2) << "\n";
    if (!options.out.empty()) io::write_json(options.out, j);
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_bench_sim(CommandSpec& c, BenchSimOptions& o) {
    c.option("--seed", o.seed, "Scene seed").show_default();
    c.option("--sweeps", o.sweeps, "Sweeps timed per configuration (median reported)")
        .range(1, 10000)
        .show_default();
    c.option("--out", o.out, "Also write the JSON to this file");
}
const Registration<BenchSimOptions> kBenchSim{
    "bench sim", Group::kEvaluation,
    "LiDAR simulation speed: full VLP-32C sweeps (57,600 rays) in a "
    "20 x 20 m room with 40 objects, on 1 and 2 threads",
    declare_bench_sim, run_bench_sim};

}  // namespace

}  // namespace makeway::apps
