// makeway bench nav / bench merge: the paper's navigation benchmark (every method on generated
// scenes of varied density), whole or in shards joined afterwards.
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "apps/nav_report.hpp"
#include "apps/nav_run.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/nav_png.hpp"
#include "io/progress.hpp"
#include "io/scene_io.hpp"
#include "io/staged_output.hpp"
#include "io/zones_io.hpp"
#include "makeway/eval/zone_bench.hpp"
#include "makeway/shape/learned_prior.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::apps {

struct BenchNavOptions {
    std::string config;
    int scenes = 25;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_nav";
    std::string model;  ///< detector weights for `ours`; empty: the default ones when present
    int threads = 2;
    double time_limit_s = 180.0;
    std::vector<std::string> methods;  ///< empty: every method (ours when weights are there)
    std::string shard;  ///< "K/N": run scenes K, K + N, ... and write partial.json (empty: every
                        ///< scene, the results)
    std::string layout =
        "random";  ///< random (densities cycle) or study_space (the paper's room, seeded)
    std::string usage = "default";     ///< how the scenes' people move furniture (their profile)
    std::string zones;                 ///< learned zones for the methods' costmaps
    int zones_sessions = 0;            ///< > 0: zones learned from this many sessions of each scene
    std::string risk_zones = "paper";  ///< paper, or truth-profile: each scene's profile as zones
    std::string shape_model;  ///< `ours` verifies against these learned shapes instead of the
                              ///< scenes' CAD models
};

struct BenchMergeOptions {
    std::vector<std::string> dirs;  ///< folders holding partial.json (one per shard)
    std::string out_dir = "out/bench_nav";
};

namespace {

constexpr const char* kPartialKind = "makeway bench nav partial";

// results.json, table.md, risk_time.png and timing.json from the runs of every scene: the same
// function for one run and for merged shards, so both give the same bytes.
void write_nav_results(const std::filesystem::path& out, const io::Json& header,
                       const io::Json& runs, const io::Json& timing, double time_limit_s) {
    const io::Json summary = summarise_nav(header, runs);
    io::write_json(out / "results.json", summary);
    const auto methods = header["methods"].get<std::vector<std::string>>();
    const io::Json timing_summary = summarise_timing(timing, methods);
    io::write_json(out / "timing.json", {{"aggregate", timing_summary}, {"runs", timing}});
    const std::string table =
        "# Navigation benchmark: " + std::to_string(header["scenes"].get<int>()) +
        " scenes, seed " + std::to_string(header["seed"].get<std::uint64_t>()) + "\n\n" +
        nav_table_markdown(summary) +
        "\nSums and means over successful runs (success = goal reached in " +
        std::to_string(static_cast<int>(time_limit_s)) +
        " s without touching a wall, pillar or piece of furniture; walking people do "
        "not avoid the robot, so contacts with them are counted apart). Avoidable risk = risk "
        "time - the least risk time any collision-free route has at top speed (unavoidable). "
        "Intervals: 2,000 bootstrap resamples of the scenes.\n\n![risk vs time](risk_time.png)\n";
    io::write_file_atomic(out / "table.md", table);
    write_risk_time_plot(out / "risk_time.png", summary);
    std::cout << table;
    for (const std::string& m : methods) {
        std::cout << m << ": control cycle " << timing_summary[m]["cycle_ms_median"].get<double>()
                  << " ms median (of the runs' medians), "
                  << timing_summary[m]["cycle_ms_p99"].get<double>() << " ms p99";
        if (m == "ours") {  // the full system drives on its own pose (LiDAR odometry fused with the
                            // wheels)
            const io::Json& a = summary["aggregate"][m];
            std::cout << "; its pose: ATE " << 100 * a["pose_ate_m_median"].get<double>()
                      << " cm median, " << 100 * a["pose_ate_m_max"].get<double>()
                      << " cm max, final error "
                      << 100 * a["final_pose_error_m_median"].get<double>() << " cm median";
        }
        std::cout << "\n";
    }
}

}  // namespace

std::optional<std::pair<int, int>> parse_shard(const std::string& text) {
    int k = -1, n = -1;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d %c %d %c", &k, &slash, &n, &extra) != 3 || slash != '/')
        return std::nullopt;
    if (n < 1 || n > 100000 || k < 0 || k >= n) return std::nullopt;
    return std::make_pair(k, n);
}

int run_bench_nav(const BenchNavOptions& options) {
    const io::SimConfig cfg = io::load_sim_config(options.config);
    const auto shard = parse_shard(options.shard.empty() ? "0/1" : options.shard);
    if (!shard)
        throw std::invalid_argument("--shard " + options.shard + ": expected K/N with 0 <= K < N");
    const bool partial = !options.shard.empty();
    io::StagedOutput staged(
        options.out_dir);  // scenes, routes, results (or the partial): all or none
    const std::filesystem::path out = staged.staging();
    // The full system `ours` joins when detector weights are there (given, or the default ones).
    std::vector<std::string> methods = eval::nav_method_names();
    std::optional<perception::Detector> detector;
    const bool ours_asked =
        std::find(options.methods.begin(), options.methods.end(), "ours") != options.methods.end();
    if (!options.model.empty() || default_model_path() || ours_asked) {
        // Names the missing default file when ours was asked for; one thread (runs go in
        // parallel instead).
        detector = load_online_detector(options.model);
        methods.push_back("ours");
    } else {
        std::cout << "no detector weights (models/detector.pt; `make model`): the full system "
                     "`ours` is left out\n";
    }
    std::unique_ptr<shape::LearnedShapePrior> prior;  // ours without CAD models: the learned shapes
    if (!options.shape_model.empty()) {
        prior = std::make_unique<shape::LearnedShapePrior>(
            std::make_shared<const shape::ShapeModel>(load_shape_model(options.shape_model)));
    }
    if (!options.methods.empty()) {
        std::erase_if(methods, [&](const std::string& m) {
            return std::find(options.methods.begin(), options.methods.end(), m) ==
                   options.methods.end();
        });
    }
    // Scene i is the same scene in every shard (its seed is seed + i); shard K takes i = K, K + N,
    // ...
    const sim::Density densities[] = {sim::Density::kSparse, sim::Density::kMedium,
                                      sim::Density::kDense};
    std::vector<int> indices;
    std::vector<sim::Scene> scenes;
    for (int i = shard->first; i < options.scenes; i += shard->second) {
        sim::SceneGenParams g;
        g.seed = options.seed + static_cast<std::uint64_t>(i);
        g.density = densities[i % 3];
        g.layout = *sim::parse_layout(options.layout);
        g.usage = *sim::parse_usage_profile(options.usage);
        g.robot = cfg.robot;
        indices.push_back(i);
        scenes.push_back(sim::generate_scene(g));
        io::write_scene(out / "scenes" / (scenes.back().name + ".yaml"), scenes.back());
    }
    const auto zones = io::load_zones(options.zones);
    // --zones-sessions: each building's zones learned from its own earlier sessions
    // (eval/zone_bench.hpp), as a robot that has driven there before would have them.
    std::vector<std::shared_ptr<const costmap::LearnedZones>> own_zones(scenes.size());
    if (options.zones_sessions > 0) {
        for (std::size_t s = 0; s < scenes.size(); ++s)
            own_zones[s] = std::make_shared<const costmap::LearnedZones>(
                eval::building_zones(scenes[s], options.zones_sessions));
    }
    // truth-profile: where each scene's furniture goes by its usage profile (eval/zone_bench.hpp).
    std::vector<std::shared_ptr<const costmap::LearnedZones>> truth_zones(scenes.size());
    if (options.risk_zones == "truth-profile") {
        for (std::size_t s = 0; s < scenes.size(); ++s)
            truth_zones[s] =
                std::make_shared<const costmap::LearnedZones>(eval::profile_zones(scenes[s]));
    }
    std::vector<std::vector<eval::NavRunResult>> results(scenes.size());
    io::ProgressBar bar("bench nav", scenes.size() * methods.size());
    std::mutex mutex;
    std::size_t done = 0;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(options.threads));
    tbb::parallel_for(std::size_t{0}, scenes.size() * methods.size(), [&](std::size_t job) {
        const std::size_t s = job / methods.size(), m = job % methods.size();
        eval::NavParams params = nav_params(cfg);
        params.seed = options.seed + static_cast<std::uint64_t>(indices[s]);
        params.time_limit_s = options.time_limit_s;
        plan_with_zones(params, own_zones[s] ? own_zones[s] : zones);
        if (truth_zones[s]) {
            costmap::AffordanceParams risk = cfg.affordance;
            risk.learned = truth_zones[s];
            params.risk_zones = risk;
        }
        eval::NavRunResult r = run_nav_method(scenes[s], methods[m], params,
                                              detector ? &*detector : nullptr, prior.get());
        std::lock_guard<std::mutex> lock(mutex);
        results[s].resize(methods.size());
        results[s][m] = std::move(r);
        bar.update(++done, scenes[s].name + " " + methods[m]);
    });
    bar.finish();

    io::Json runs = io::Json::array(), timing = io::Json::array();
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<io::DrivenPath> paths;
        for (const auto& r : results[s]) {
            io::Json j = run_to_json(r, false);
            j["scene"] = scenes[s].name;
            j["scene_index"] = indices[s];
            j["density"] = scenes[s].density;
            runs.push_back(j);
            io::Json t = run_timing_json(r);
            t["scene"] = scenes[s].name;
            t["scene_index"] = indices[s];
            timing.push_back(t);
            paths.push_back({r.method + (r.success ? "" : " (failed: " + r.failure + ")") +
                                 ": risk " + std::to_string(r.risk_time_s).substr(0, 4) +
                                 " s, time " + std::to_string(r.time_s).substr(0, 5) + " s",
                             r.trajectory});
        }
        io::write_nav_png(out / "routes" / (scenes[s].name + ".png"), scenes[s], Costmap{}, paths,
                          {}, scenes[s].name + ": every method", cfg.affordance);
    }
    // What every shard of one benchmark shares; a merge refuses partials that differ in it.
    io::Json header = {
        {"scenes", options.scenes},
        {"seed", options.seed},
        {"methods", methods},
        {"time_limit_s", options.time_limit_s},
        {"layout", options.layout},
        {"shape_model", options.shape_model},  // ours with learned shapes: a different benchmark
        {"config", options.config.empty() ? std::string() : io::read_file(options.config)}};
    // Zones and usage only when asked for: the paper's benchmark keeps its header.
    if (options.usage != "default") header["usage"] = options.usage;
    if (!options.zones.empty()) header["zones"] = io::read_file(options.zones);
    if (options.zones_sessions > 0) header["zones_sessions"] = options.zones_sessions;
    if (options.risk_zones != "paper") header["risk_zones"] = options.risk_zones;
    if (partial) {
        io::Json p = {{"kind", kPartialKind},
                      {"header", header},
                      {"shard", {{"index", shard->first}, {"count", shard->second}}},
                      {"runs", runs},
                      {"timing", timing}};
        io::write_json(out / "partial.json", p);
        staged.commit();
        std::cout << "bench nav shard " << shard->first << "/" << shard->second << ": "
                  << scenes.size() << " scenes, " << runs.size() << " runs in "
                  << (std::filesystem::path(options.out_dir) / "partial.json").string()
                  << " (join with `makeway bench merge`)\n";
        return 0;
    }
    write_nav_results(out, header, runs, timing, options.time_limit_s);
    staged.commit();
    return 0;
}

int run_bench_merge(const BenchMergeOptions& options) {
    // Read and check every partial before writing anything.
    struct Part {
        std::filesystem::path dir;
        io::Json json;
    };
    std::vector<Part> parts;
    for (const std::string& d : options.dirs) {
        const std::filesystem::path file = std::filesystem::path(d) / "partial.json";
        io::Json j = io::read_json(file);
        if (!j.is_object() || j.value("kind", "") != kPartialKind || !j.contains("header") ||
            !j.contains("shard") || !j.contains("runs") || !j.contains("timing")) {
            throw io::FileError(file.string(), "not a `makeway bench nav --shard` partial result");
        }
        parts.push_back({d, std::move(j)});
    }
    if (parts.empty()) throw std::invalid_argument("bench merge: no partial results given");
    const io::Json& header = parts.front().json["header"];
    const int count = parts.front().json["shard"]["count"].get<int>();
    std::vector<int> seen(static_cast<std::size_t>(count), 0);
    for (const Part& p : parts) {
        const std::string name = (p.dir / "partial.json").string();
        if (p.json["header"] != header)
            throw io::FileError(name,
                                "a different benchmark (scenes, seed, methods, time limit, shape "
                                "model or configuration) than " +
                                    (parts.front().dir / "partial.json").string());
        if (p.json["shard"]["count"].get<int>() != count)
            throw io::FileError(name, "shard count differs from the first partial's");
        const int k = p.json["shard"]["index"].get<int>();
        if (k < 0 || k >= count) throw io::FileError(name, "shard index out of range");
        if (seen[k]++)
            throw io::FileError(
                name, "shard " + std::to_string(k) + "/" + std::to_string(count) + " given twice");
    }
    for (int k = 0; k < count; ++k) {
        if (!seen[k])
            throw io::FileError((parts.front().dir / "partial.json").string(),
                                "shard " + std::to_string(k) + "/" + std::to_string(count) +
                                    " is missing from the folders given");
    }
    // Runs in the order one unsharded run writes them: scene index, then method order.
    const auto methods = header["methods"].get<std::vector<std::string>>();
    auto rank = [&](const io::Json& r) {
        const auto it = std::find(methods.begin(), methods.end(), r["method"].get<std::string>());
        return std::make_pair(r["scene_index"].get<int>(), static_cast<int>(it - methods.begin()));
    };
    io::Json runs = io::Json::array(), timing = io::Json::array();
    for (const Part& p : parts) {
        for (const io::Json& r : p.json["runs"]) runs.push_back(r);
        for (const io::Json& t : p.json["timing"]) timing.push_back(t);
    }
    std::stable_sort(runs.begin(), runs.end(),
                     [&](const io::Json& a, const io::Json& b) { return rank(a) < rank(b); });
    std::stable_sort(timing.begin(), timing.end(),
                     [&](const io::Json& a, const io::Json& b) { return rank(a) < rank(b); });
    const std::size_t expected =
        static_cast<std::size_t>(header["scenes"].get<int>()) * methods.size();
    if (runs.size() != expected) {
        throw io::FileError((parts.front().dir / "partial.json").string(),
                            "the partials hold " + std::to_string(runs.size()) +
                                " runs, the benchmark " + std::to_string(expected));
    }
    io::StagedOutput staged(options.out_dir);
    const std::filesystem::path out = staged.staging();
    for (const Part& p : parts) {  // every shard's scenes and route pictures
        for (const char* sub : {"scenes", "routes"}) {
            if (!std::filesystem::is_directory(p.dir / sub)) continue;
            std::filesystem::create_directories(out / sub);
            for (const auto& e : std::filesystem::directory_iterator(p.dir / sub)) {
                std::filesystem::copy_file(e.path(), out / sub / e.path().filename(),
                                           std::filesystem::copy_options::overwrite_existing);
            }
        }
    }
    write_nav_results(out, header, runs, timing, header["time_limit_s"].get<double>());
    staged.commit();
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_bench_nav(CommandSpec& c, BenchNavOptions& nav_o) {
    c.option("--config", nav_o.config, "YAML configuration: lidar, robot and affordance sections");
    c.option("--scenes", nav_o.scenes, "Number of scenes (density cycles sparse, medium, dense)")
        .range(1, 1000)
        .show_default();
    c.option("--seed", nav_o.seed, "Seed of the first scene").show_default();
    c.option("--out", nav_o.out_dir, "Output folder").show_default();
    c.option("--threads", nav_o.threads, "Runs in parallel").range(1, 256).show_default();
    c.option("--model", nav_o.model,
             "Detector weights for the full system ours (default: models/detector.pt "
             "when present; without weights ours is left out)");
    c.option("--shape-model", nav_o.shape_model,
             "Shape networks: `ours` verifies against its learned shapes instead of "
             "the scenes' CAD models")
        .existing_file();
    c.option("--methods", nav_o.methods,
             "Only these methods (con, oppo, gt-perc, ours), comma-separated")
        .delimiter(',')
        .choices({"con", "oppo", "gt-perc", "ours"});
    c.option("--time-limit", nav_o.time_limit_s, "Seconds per run before it counts as failed [s]")
        .range(1.0, 3600.0)
        .show_default();
    c.option("--layout", nav_o.layout,
             "random (densities cycle sparse, medium, dense) or study_space (the paper's "
             "room of 12 tables and 22 chairs, one per seed)")
        .choices({"random", "study_space"})
        .show_default();
    c.option("--usage", nav_o.usage,
             "How the generated scenes' people move their furniture (their usage profile; "
             "README): default, pulled_back, sideways, tables_nudged")
        .choices(sim::usage_profile_names())
        .show_default();
    const OptionSpec& zones = c.option("--zones", nav_o.zones,
                                       "Learned zones (makeway learn-zones, bench zones) for every "
                                       "method's affordance layer instead of the hand-drawn ones")
                                  .existing_file();
    c.option("--zones-sessions", nav_o.zones_sessions,
             "K > 0: every method plans with zones learned from K sessions of its own building "
             "(the sessions' boxes, identities hidden; never the sessions truth-profile scores "
             "on) instead of the hand-drawn ones; 0: off")
        .range(0, 100)
        .check(
            [](const std::string& v) {
                return std::atoi(v.c_str()) == 1 ? "one session shows no motion: 0 or 2 and more"
                                                 : "";
            },
            "K")
        .excludes(zones)
        .show_default();
    c.option("--risk-zones", nav_o.risk_zones,
             "What risk time is scored against: paper (the hand-drawn zones, Table II) or "
             "truth-profile (where each scene's usage profile moves its furniture)")
        .choices({"paper", "truth-profile"})
        .show_default();
    c.option("--shard", nav_o.shard,
             "K/N: run only scenes K, K+N, K+2N, ... (0 <= K < N) and write partial.json; "
             "`makeway bench merge` joins the N partials into the unsharded results")
        .check(
            [](const std::string& v) {
                return parse_shard(v) ? std::string() : "expected K/N with 0 <= K < N";
            },
            "K/N");
}
const Registration<BenchNavOptions> kBenchNav{
    "bench nav", Group::kEvaluation,
    "The navigation benchmark (the paper's Table II): every method on "
    "generated scenes of varied density; writes results.json, table.md "
    "and one PNG per scene",
    declare_bench_nav, run_bench_nav};

void declare_bench_merge(CommandSpec& c, BenchMergeOptions& merge_o) {
    c.option("dirs", merge_o.dirs, "Folders holding partial.json, one per shard, in any order")
        .required()
        .existing_directory();
    c.option("--out", merge_o.out_dir, "Output folder").show_default();
}
const Registration<BenchMergeOptions> kBenchMerge{
    "bench merge", Group::kEvaluation,
    "Join `bench nav --shard K/N` partial results (one folder per shard) into "
    "exactly the results one unsharded run writes",
    declare_bench_merge, run_bench_merge};

}  // namespace

}  // namespace makeway::apps
