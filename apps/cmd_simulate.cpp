// makeway simulate: drive the simulated Jackal through a scene and record every sweep with its
// ground truth.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "apps/recording.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/scene_io.hpp"
#include "io/sim_config.hpp"
#include "io/text_scan.hpp"

namespace makeway::apps {

struct SimulateOptions {
    std::string config;  ///< lidar, robot and odometry sections; empty: built-in defaults
    std::string scene;
    std::string route = "auto";
    int frames = 100;
    std::string out_dir;
    std::string format = "pcd";
    std::uint64_t seed = 0;
    int threads = 1;
    bool allow_outside_paths = false;  ///< the scene's meshes may lie outside its folder
};

namespace {

// A route file: one "x y" pair [m] per line, '#' comments.
std::vector<Eigen::Vector2d> read_route(const std::string& path) {
    const std::string text = io::read_file(path);
    std::vector<Eigen::Vector2d> route;
    std::size_t pos = 0, line_no = 0;
    while (const auto line = io::next_line(text, pos)) {
        ++line_no;
        const auto words = io::split_words(*line);
        if (words.empty() || words[0].front() == '#') continue;
        double xy[2];
        for (int k = 0; k < 2; ++k) {
            if (words.size() != 2 ||
                std::sscanf(std::string(words[k]).c_str(), "%lf", &xy[k]) != 1 ||
                !std::isfinite(xy[k])) {
                throw io::FileError(
                    path, "line " + std::to_string(line_no) + ": expected two numbers 'x y'");
            }
        }
        route.emplace_back(xy[0], xy[1]);
    }
    if (route.empty()) throw io::FileError(path, "no route points");
    return route;
}

}  // namespace

int run_simulate(const SimulateOptions& options) {
    const io::SimConfig cfg = io::load_sim_config(options.config);
    const sim::Scene scene =
        io::read_scene(options.scene, {.allow_outside_paths = options.allow_outside_paths});
    sim::SequenceParams params;
    params.lidar = cfg.lidar;
    params.robot = cfg.robot;
    params.odometry = cfg.odometry;
    params.seed = options.seed;
    params.lidar.num_threads = options.threads;
    std::vector<Eigen::Vector2d> route;
    if (options.route == "auto") {
        route = auto_route(scene, params.robot, options.scene);
    } else {
        route = read_route(options.route);
        route.insert(route.begin(), Eigen::Vector2d(scene.start.x_m, scene.start.y_m));
    }
    const RecordingSummary s =
        record_sequence(scene, route, params, {.frames = options.frames, .format = options.format},
                        options.out_dir, options.scene);
    std::cout << "wrote " << s.frames << " frames to " << options.out_dir << " (distance "
              << s.distance_m << " m, goal " << (s.reached_goal ? "reached" : "not reached") << ", "
              << s.ms_per_frame << " ms per frame)\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_simulate(CommandSpec& c, SimulateOptions& o) {
    c.option("--scene", o.scene, "Scene file (.yaml) from `makeway scene` or written by hand")
        .required();
    c.option("--config", o.config,
             "YAML configuration: its lidar, robot and odometry sections are used "
             "(default: built-in VLP-32C on a Jackal; see config/default.yaml)");
    c.option("--route", o.route,
             "auto (shortest safe route start -> waypoint -> goal) or a text file "
             "of 'x y' points [m], one per line")
        .show_default();
    c.option("--frames", o.frames, "Sweeps to record (10 per second)")
        .range(1, 1000000)
        .show_default();
    c.option("--out", o.out_dir,
             "Output folder: clouds/, objects/, poses_gt.txt, odometry.txt, "
             "scene.png, summary.json")
        .required();
    c.option("--format", o.format,
             "Cloud format: pcd (binary, with labels), bin (KITTI, labels "
             "in SemanticKITTI .label files) or bag (a ROS 1 bag, drive.bag, as a robot "
             "records it: /velodyne_points, /odom, /tf_static; the truth on /ground_truth/*)")
        .choices({"pcd", "bin", "bag"})
        .show_default();
    c.option("--seed", o.seed, "Seed of sensor noise and odometry drift").show_default();
    c.option("--threads", o.threads, "Ray-casting threads").range(1, 256).show_default();
    c.flag("--allow-outside-paths", o.allow_outside_paths,
           "Let the scene's `mesh:` paths leave the scene's folder (absolute, ../); off: a "
           "scene reads only "
           "files beside it");
}
const Registration<SimulateOptions> kSimulate{
    "simulate", Group::kSimulation,
    "Drive the simulated Jackal (VLP-32C LiDAR, 10 Hz) through a "
    "scene and record every sweep with ground truth",
    declare_simulate, run_simulate};

}  // namespace

}  // namespace makeway::apps
