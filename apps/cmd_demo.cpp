// The demo: the longest end-to-end path that exists so far. A procedural scene from the
// configuration, the simulated Jackal driving it with its VLP-32C, every sweep recorded with ground
// truth, and the recorded clouds checked through every point-cloud format.
#include <cstring>
#include <filesystem>
#include <iostream>

#include "apps/commands.hpp"
#include "apps/recording.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway::apps {
namespace {

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_cloud(const PointCloud& a, const PointCloud& b, bool xyzi_only) {
    const bool xyzi = same_bits(a.xyz, b.xyz) && same_bits(a.intensity, b.intensity);
    if (xyzi_only) return xyzi;
    return xyzi && same_bits(a.ring, b.ring) && same_bits(a.time_s, b.time_s) && same_bits(a.label, b.label) &&
           same_bits(a.instance, b.instance);
}

}  // namespace

int run_demo(const DemoOptions& options) {
    const io::Config cfg = options.config.empty() ? io::Config{} : io::load_config(options.config);
    const std::filesystem::path out = options.out_dir;

    // Scene: a room with tables, chairs, people and a mission (start -> waypoint -> goal).
    std::cout << "makeway demo: generating a " << sim::to_string(cfg.scene.density) << " scene (seed "
              << cfg.scene.seed << ")\n";
    sim::Scene scene;
    try {
        scene = sim::generate_scene(cfg.scene);
    } catch (const std::runtime_error& e) {
        throw io::FileError(options.config.empty() ? "built-in configuration" : options.config, e.what());
    }
    std::cout << "  " << write_scene_with_picture(out / "scene.yaml", scene) << "\n";

    // Drive: the robot follows the route while the LiDAR records every sweep.
    sim::SequenceParams params;
    params.lidar = cfg.lidar;
    params.robot = cfg.robot;
    params.odometry = cfg.odometry;
    params.seed = cfg.simulation.seed;
    const auto route = auto_route(scene, params.robot, "scene " + scene.name);
    // The demo keeps one cloud per second (ground truth for every sweep) and stops at the goal.
    const RecordingSummary rec =
        record_sequence(scene, route, params,
                        {.frames = cfg.simulation.frames, .format = "pcd", .cloud_every = 10, .stop_at_goal = true},
                        out / "sequence", (out / "scene.yaml").string());

    // Formats: the first sweep through PLY and KITTI, read back and compared bit for bit.
    const PointCloud first = io::read_point_cloud(out / "sequence" / "clouds" / "000000.pcd").cloud;
    bool exact = true;
    for (const char* name : {"first_sweep.ply", "first_sweep.bin"}) {
        io::write_point_cloud(out / name, first);
        exact &= same_cloud(first, io::read_point_cloud(out / name).cloud, std::strstr(name, ".bin") != nullptr);
    }
    const std::size_t n_points = first.size();
    std::size_t labelled[kNumSemanticLabels] = {};
    for (std::uint8_t l : first.label) labelled[l < kNumSemanticLabels ? l : 0]++;
    io::Json labels;
    for (int l = 0; l < kNumSemanticLabels; ++l) labels[std::string(to_string(static_cast<SemanticLabel>(l)))] = labelled[l];

    io::write_json(out / "summary.json", {{"scene", scene.name},
                                          {"objects", scene.objects.size()},
                                          {"frames", rec.frames},
                                          {"reached_goal", rec.reached_goal},
                                          {"frames_in_collision", rec.frames_in_collision},
                                          {"distance_m", rec.distance_m},
                                          {"ms_per_frame", rec.ms_per_frame},
                                          {"first_sweep_points", n_points},
                                          {"first_sweep_points_by_label", labels},
                                          {"format_round_trips_exact", exact}});
    std::cout << "  drove " << rec.distance_m << " m in " << rec.frames << " sweeps ("
              << (rec.reached_goal ? "goal reached" : "goal not reached yet") << ", "
              << rec.frames_in_collision << " frames in collision), " << rec.ms_per_frame << " ms per sweep\n"
              << "  first sweep: " << n_points << " points, " << labelled[static_cast<int>(SemanticLabel::kChair)]
              << " on chairs, " << labelled[static_cast<int>(SemanticLabel::kTable)] << " on tables\n"
              << "  PLY and KITTI round trips exact: " << (exact ? "yes" : "NO") << "\n"
              << "  wrote " << (out / "scene.png").string() << ", " << (out / "sequence").string() << "/, "
              << (out / "summary.json").string() << "\n";
    return exact ? 0 : 1;
}

}  // namespace makeway::apps
