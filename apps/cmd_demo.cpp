// The demo: the longest end-to-end path that exists so far. The paper's study-space scene (12
// tables, 22 chairs), a short labelled recording of the VLP-32C on the Jackal, and the navigation
// benchmark's methods driving start -> waypoint -> goal, with a report.
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "apps/nav_report.hpp"
#include "apps/nav_run.hpp"
#include "apps/recording.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/nav_png.hpp"
#include "io/point_cloud_io.hpp"
#include "io/sim_config.hpp"
#include "io/staged_output.hpp"

namespace makeway::apps {

struct DemoOptions {
    std::string config;  ///< empty: built-in defaults
    std::string out_dir = "out/demo";
};

namespace {

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_cloud(const PointCloud& a, const PointCloud& b, bool xyzi_only) {
    const bool xyzi = same_bits(a.xyz, b.xyz) && same_bits(a.intensity, b.intensity);
    if (xyzi_only) return xyzi;
    return xyzi && same_bits(a.ring, b.ring) && same_bits(a.time_s, b.time_s) &&
           same_bits(a.label, b.label) && same_bits(a.instance, b.instance);
}

}  // namespace

int run_demo(const DemoOptions& options) {
    const io::SimConfig cfg = io::load_sim_config(options.config);
    // Everything is written to a staging folder and moved into place at the end: all or nothing.
    io::StagedOutput staged(options.out_dir);
    const std::filesystem::path out = staged.staging();
    const std::filesystem::path shown = options.out_dir;

    // Scene.
    sim::Scene scene;
    try {
        scene = sim::generate_scene(cfg.scene);
    } catch (const std::runtime_error& e) {
        throw io::FileError(options.config.empty() ? "built-in configuration" : options.config,
                            e.what());
    }
    std::cout << "makeway demo\n  scene " << write_scene_with_picture(out / "scene.yaml", scene)
              << "\n";

    // Sensor data: a short recording with ground truth, checked through every cloud format.
    sim::SequenceParams seq;
    seq.lidar = cfg.lidar;
    seq.robot = cfg.robot;
    seq.odometry = cfg.odometry;
    seq.seed = cfg.simulation.seed;
    const auto route = auto_route(scene, seq.robot, "scene " + scene.name);
    const RecordingSummary rec =
        record_sequence(scene, route, seq, {.frames = cfg.simulation.frames, .cloud_every = 10},
                        out / "sequence", (shown / "scene.yaml").string());
    const PointCloud first = io::read_point_cloud(out / "sequence" / "clouds" / "000000.pcd").cloud;
    bool exact = true;
    for (const char* name : {"first_sweep.ply", "first_sweep.bin"}) {
        io::write_point_cloud(out / name, first);
        exact &= same_cloud(first, io::read_point_cloud(out / name).cloud,
                            std::strstr(name, ".bin") != nullptr);
    }
    std::cout << "  recorded " << rec.frames << " sweeps (" << first.size()
              << " points in the first), format round trips " << (exact ? "exact" : "NOT exact")
              << "\n";

    // Navigation: every method on the same scene, with the same planners.
    const eval::NavParams nav = nav_params(cfg);
    std::vector<io::DrivenPath> paths;
    io::Json runs_json = io::Json::array();
    // The full system `ours` runs when the default detector weights are there.
    std::vector<std::string> methods = eval::nav_method_names();
    std::optional<perception::Detector> detector;
    if (const auto model = default_model_path()) {
        detector = load_online_detector(model->string());
        methods.push_back("ours");
    } else {
        std::cout << "  no detector weights (models/detector.pt; `make model`): skipping the full "
                     "system `ours`\n";
    }
    for (const std::string& name : methods) {
        eval::NavRunResult r = run_nav_method(scene, name, nav, detector ? &*detector : nullptr);
        const std::string line = name + ": " +
                                 (r.success ? "success" : "failed (" + r.failure + ")") + ", " +
                                 std::to_string(r.time_s).substr(0, 5) + " s, risk " +
                                 std::to_string(r.risk_time_s).substr(0, 4) + " s, " +
                                 std::to_string(r.distance_m).substr(0, 5) + " m";
        std::cout << "  navigate " << line << "\n";
        std::vector<io::DrivenPath> drawn{{name, r.trajectory}};
        if (!r.estimated_trajectory.empty() && r.method == "ours")
            drawn.push_back({"ours, believed (wheel odometry)", r.estimated_trajectory});
        io::write_nav_png(out / "routes" / (name + ".png"), scene, r.final_costmap, drawn,
                          r.last_plan, scene.name + " / " + line, nav.system.navigator.affordance);
        paths.push_back({line, r.trajectory});
        runs_json.push_back(run_to_json(r, true));
        runs_json.back()["scene"] = scene.name;
        runs_json.back()["scene_index"] = 0;
    }
    io::write_nav_png(out / "routes" / "all_methods.png", scene, Costmap{}, paths, {},
                      scene.name + ": every method", nav.system.navigator.affordance);
    const io::Json summary = summarise_nav(
        {{"scenes", 1}, {"seed", cfg.simulation.seed}, {"methods", methods}}, runs_json);
    const io::Json& agg = summary["aggregate"];
    const std::string report =
        "# makeway demo report\n\nScene `" + scene.name + "` (" +
        std::to_string(scene.objects.size()) +
        " objects; `scene.png`). Each method drives start -> waypoint -> goal with the same A* and "
        "DWA; "
        "risk time is the time the robot's centre spends inside the ground-truth affordance "
        "zones.\n\n" +
        nav_table_markdown(summary) +
        "\n![every method](routes/all_methods.png)\n\nPer method, with its final costmap: "
        "[con](routes/con.png), [oppo](routes/oppo.png), [gt-perc](routes/gt-perc.png)" +
        (detector ? std::string(", [ours](routes/ours.png) (the online system on wheel odometry: "
                                "detector, verification, object map; "
                                "its believed path drawn beside the true one)")
                  : std::string()) +
        ".\n";
    io::write_file_atomic(out / "report.md", report);
    io::write_json(out / "summary.json", {{"scene", scene.name},
                                          {"objects", scene.objects.size()},
                                          {"recorded_frames", rec.frames},
                                          {"first_sweep_points", first.size()},
                                          {"format_round_trips_exact", exact},
                                          {"navigation", runs_json},
                                          {"aggregate", agg}});
    staged.commit();
    std::cout << "  wrote " << (shown / "report.md").string() << ", " << (shown / "routes").string()
              << "/, " << (shown / "summary.json").string() << "\n";
    return exact ? 0 : 1;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_demo(CommandSpec& c, DemoOptions& o) {
    c.option("--config", o.config,
             "YAML configuration (default: built-in defaults; see "
             "config/default.yaml)");
    c.option("--out", o.out_dir, "Output folder").show_default();
}
const Registration<DemoOptions> kDemo{"demo", Group::kSetup,
                                      "Run the longest end-to-end path that exists on the "
                                      "built-in default scene and write its outputs",
                                      declare_demo, run_demo};

}  // namespace

}  // namespace makeway::apps
