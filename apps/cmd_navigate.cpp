// makeway navigate / makeway bench nav: closed-loop navigation on the simulator, one run or the
// paper's benchmark (every method on generated scenes of varied density).
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>

#include "apps/commands.hpp"
#include "io/json_io.hpp"
#include "apps/model_path.hpp"
#include "apps/nav_report.hpp"
#include "apps/nav_run.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/map_server_io.hpp"
#include "io/nav_png.hpp"
#include "io/progress.hpp"
#include "io/scene_io.hpp"
#include "io/staged_output.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::apps {

int run_navigate(const NavigateOptions& options) {
    const io::Config cfg = options.config.empty() ? io::Config{} : io::load_config(options.config);
    const sim::Scene scene = io::read_scene(options.scene, {.allow_outside_paths = options.allow_outside_paths});
    eval::NavParams params = nav_params(cfg);
    params.seed = options.seed;
    params.time_limit_s = options.time_limit_s;
    if (!options.map.empty()) params.static_map = io::read_map_server(options.map);
    std::optional<perception::Detector> detector;
    if (options.method == "ours") detector = load_detector(options.model);
    const eval::NavRunResult r = run_nav_method(scene, options.method, params, detector ? &*detector : nullptr);
    io::StagedOutput staged(options.out_dir);  // run.json, costmap.yaml/.pgm, route.png: all or none
    const std::filesystem::path out = staged.staging();
    io::Json j = run_to_json(r, true);
    j["scene"] = options.scene;
    io::write_json(out / "run.json", j);
    io::write_map_server(out / "costmap.yaml", r.final_costmap);
    io::write_nav_png(out / "route.png", scene, r.final_costmap, {{options.method, r.trajectory}}, r.last_plan,
                      scene.name + " / " + options.method + ": " + (r.success ? "success" : "failed (" + r.failure + ")") +
                          ", " + std::to_string(r.time_s).substr(0, 5) + " s, risk " +
                          std::to_string(r.risk_time_s).substr(0, 4) + " s",
                      params.system.navigator.affordance);
    staged.commit();
    std::cout << io::dump_json(j) << "\n";
    return 0;
}

int run_bench_nav(const BenchNavOptions& options) {
    const io::Config cfg = options.config.empty() ? io::Config{} : io::load_config(options.config);
    io::StagedOutput staged(options.out_dir);  // scenes, routes, results.json, table.md: all or none
    const std::filesystem::path out = staged.staging();
    // The full system `ours` joins when detector weights are there (given, or the default ones).
    std::vector<std::string> methods = eval::nav_method_names();
    std::optional<perception::Detector> detector;
    const bool ours_asked = std::find(options.methods.begin(), options.methods.end(), "ours") != options.methods.end();
    if (!options.model.empty() || default_model_path() || ours_asked) {
        detector = load_detector(options.model);  // names the missing default file when ours was asked for
        perception::set_inference_threads(1);  // runs go in parallel instead
        methods.push_back("ours");
    } else {
        std::cout << "no detector weights (models/detector.pt; `make model`): the full system `ours` is left out\n";
    }
    if (!options.methods.empty()) {
        std::erase_if(methods, [&](const std::string& m) {
            return std::find(options.methods.begin(), options.methods.end(), m) == options.methods.end();
        });
    }
    const sim::Density densities[] = {sim::Density::kSparse, sim::Density::kMedium, sim::Density::kDense};
    std::vector<sim::Scene> scenes;
    for (int i = 0; i < options.scenes; ++i) {
        sim::SceneGenParams g;
        g.seed = options.seed + static_cast<std::uint64_t>(i);
        g.density = densities[i % 3];
        g.robot = cfg.robot;
        scenes.push_back(sim::generate_scene(g));
        io::write_scene(out / "scenes" / (scenes.back().name + ".yaml"), scenes.back());
    }
    std::vector<std::vector<eval::NavRunResult>> results(scenes.size());
    io::ProgressBar bar("bench nav", scenes.size() * methods.size());
    std::mutex mutex;
    std::size_t done = 0;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(options.threads));
    tbb::parallel_for(std::size_t{0}, scenes.size() * methods.size(), [&](std::size_t job) {
        const std::size_t s = job / methods.size(), m = job % methods.size();
        eval::NavParams params = nav_params(cfg);
        params.seed = options.seed + s;
        params.time_limit_s = options.time_limit_s;
        eval::NavRunResult r = run_nav_method(scenes[s], methods[m], params, detector ? &*detector : nullptr);
        std::lock_guard<std::mutex> lock(mutex);
        results[s].resize(methods.size());
        results[s][m] = std::move(r);
        bar.update(++done, scenes[s].name + " " + methods[m]);
    });
    bar.finish();

    std::vector<eval::NavRunResult> all;
    io::Json runs = io::Json::array();
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<io::DrivenPath> paths;
        for (const auto& r : results[s]) {
            io::Json j = run_to_json(r, false);
            j["scene"] = scenes[s].name;
            j["density"] = scenes[s].density;
            runs.push_back(j);
            paths.push_back({r.method + (r.success ? "" : " (failed: " + r.failure + ")") + ": risk " +
                                 std::to_string(r.risk_time_s).substr(0, 4) + " s, time " + std::to_string(r.time_s).substr(0, 5) + " s",
                             r.trajectory});
            all.push_back(r);
        }
        io::write_nav_png(out / "routes" / (scenes[s].name + ".png"), scenes[s], Costmap{}, paths, {},
                          scenes[s].name + ": every method", cfg.affordance);
    }
    const io::Json agg = aggregate_runs(all, methods);
    io::write_json(out / "results.json", {{"scenes", options.scenes}, {"seed", options.seed}, {"runs", runs}, {"aggregate", agg}});
    const std::string table = "# Navigation benchmark: " + std::to_string(options.scenes) + " scenes, seed " +
                              std::to_string(options.seed) + "\n\n" + table_markdown(agg, methods, options.scenes) +
                              "\nSums and means over successful runs (success = goal reached in " +
                              std::to_string(static_cast<int>(options.time_limit_s)) +
                              " s without touching a wall, pillar or piece of furniture; walking people do "
                              "not avoid the robot, so contacts with them are counted apart).\n";
    io::write_file_atomic(out / "table.md", table);
    staged.commit();
    std::cout << table;
    for (const std::string& m : methods) {
        std::cout << m << ": control cycle " << agg[m]["cycle_ms_median"].get<double>() << " ms median, "
                  << agg[m]["cycle_ms_p99"].get<double>() << " ms p99";
        if (m == "ours") {  // the full system drives on its own pose (LiDAR odometry fused with the wheels)
            std::cout << "; its pose: ATE " << 100 * agg[m]["pose_ate_m_median"].get<double>() << " cm median, "
                      << 100 * agg[m]["pose_ate_m_max"].get<double>() << " cm max, final error "
                      << 100 * agg[m]["final_pose_error_m_median"].get<double>() << " cm median";
        }
        std::cout << "\n";
    }
    return 0;
}

}  // namespace makeway::apps
