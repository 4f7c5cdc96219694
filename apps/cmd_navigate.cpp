// makeway navigate: one closed-loop run of one method on the simulator (the benchmark over many
// scenes is cmd_bench_nav.cpp).
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "apps/nav_report.hpp"
#include "apps/nav_run.hpp"
#include "io/json_io.hpp"
#include "io/map_server_io.hpp"
#include "io/nav_png.hpp"
#include "io/scene_io.hpp"
#include "io/staged_output.hpp"
#include "io/zones_io.hpp"

namespace makeway::apps {

struct NavigateOptions {
    std::string config;  ///< lidar, robot and affordance sections; empty: built-in defaults
    std::string scene;
    std::string method = "gt-perc";
    std::string map;    ///< optional map_server YAML for the static layer
    std::string model;  ///< detector weights for `ours`; empty: the default ones
    std::string out_dir;
    std::uint64_t seed = 0;
    double time_limit_s = 180.0;
    bool allow_outside_paths = false;  ///< the scene's meshes may lie outside its folder
    std::string zones;  ///< learned zones for the method's costmap (risk stays on the paper's)
};

int run_navigate(const NavigateOptions& options) {
    const io::SimConfig cfg = io::load_sim_config(options.config);
    const sim::Scene scene =
        io::read_scene(options.scene, {.allow_outside_paths = options.allow_outside_paths});
    eval::NavParams params = nav_params(cfg);
    params.seed = options.seed;
    params.time_limit_s = options.time_limit_s;
    plan_with_zones(params, io::load_zones(options.zones));
    if (!options.map.empty()) params.static_map = io::read_map_server(options.map);
    std::optional<perception::Detector> detector;
    if (options.method == "ours") detector = load_online_detector(options.model);
    const eval::NavRunResult r =
        run_nav_method(scene, options.method, params, detector ? &*detector : nullptr);
    io::StagedOutput staged(
        options.out_dir);  // run.json, costmap.yaml/.pgm, route.png: all or none
    const std::filesystem::path out = staged.staging();
    io::Json j = run_to_json(r, true);
    j["scene"] = options.scene;
    io::write_json(out / "run.json", j);
    io::write_map_server(out / "costmap.yaml", r.final_costmap);
    io::write_nav_png(out / "route.png", scene, r.final_costmap, {{options.method, r.trajectory}},
                      r.last_plan,
                      scene.name + " / " + options.method + ": " +
                          (r.success ? "success" : "failed (" + r.failure + ")") + ", " +
                          std::to_string(r.time_s).substr(0, 5) + " s, risk " +
                          std::to_string(r.risk_time_s).substr(0, 4) + " s",
                      params.system.navigator.affordance);
    staged.commit();
    std::cout << io::dump_json(j) << "\n";
    return 0;
}

namespace {

void declare_navigate(CommandSpec& c, NavigateOptions& o) {
    c.option("--scene", o.scene, "Scene file (.yaml)").required();
    c.option("--method", o.method,
             "con (no semantics, inflation 3x robot radius), oppo (no semantics, "
             "inflation = robot radius), gt-perc (affordance zones from ground truth), "
             "ours (the online system on its own pose from wheel odometry: detector, "
             "verification, object map)")
        .choices({"con", "oppo", "gt-perc", "ours"})
        .show_default();
    c.option("--model", o.model, "Detector weights for ours (default: models/detector.pt)");
    c.option("--config", o.config,
             "YAML configuration: lidar, robot and affordance sections "
             "(default: built-in; see config/default.yaml)");
    c.option("--map", o.map,
             "Static map in map_server format (YAML + PGM) instead of the scene's walls "
             "and pillars; its resolution and origin become the costmap's");
    c.option("--out", o.out_dir,
             "Output folder: run.json, route.png, costmap.yaml/.pgm (master grid, "
             "map_server format)")
        .required();
    c.option("--seed", o.seed, "Sensor-noise seed").show_default();
    c.option("--time-limit", o.time_limit_s, "Seconds before the run counts as failed [s]")
        .range(1.0, 3600.0)
        .show_default();
    c.option("--zones", o.zones,
             "Learned zones (makeway learn-zones) for the method's affordance layer instead of "
             "the hand-drawn ones; risk time stays scored on the hand-drawn zones")
        .existing_file();
    c.flag("--allow-outside-paths", o.allow_outside_paths,
           "Let the scene's `mesh:` paths leave the scene's folder (absolute, ../); off: a "
           "scene reads only "
           "files beside it");
}
const Registration<NavigateOptions> kNavigate{
    "navigate", Group::kSimulation,
    "Drive the simulated Jackal start -> waypoint -> goal with the "
    "layered costmap, A* and DWA at 10 Hz; writes run.json and route.png",
    declare_navigate, run_navigate};

}  // namespace

}  // namespace makeway::apps
