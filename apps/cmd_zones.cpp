// `makeway learn-zones`: affordance zones learned from labelled sessions of a building (issue 36).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "apps/command.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/tracking_io.hpp"
#include "io/zones_io.hpp"
#include "makeway/eval/zone_bench.hpp"
#include "makeway/zones/zone_learning.hpp"

namespace makeway::apps {
namespace fs = std::filesystem;

namespace {

// The objects of one `makeway label` output (objects.json), as place `place`.
std::vector<zones::SessionObject> read_labelled_objects(const fs::path& folder, int place) {
    const fs::path path = folder / "objects.json";
    if (!fs::is_regular_file(path))
        throw io::FileError(folder.string(),
                            "not a makeway label output (objects.json is missing)");
    const io::Json j = io::read_json(path);
    std::vector<zones::SessionObject> out;
    try {
        if (!j.is_object() || !j.contains("objects") || !j["objects"].is_array())
            throw io::FormatError("'objects' must be a list");
        std::size_t index = 0;
        for (const io::Json& o : j["objects"]) {
            const std::string where = "objects[" + std::to_string(index++) + "]: ";
            if (!o.is_object() || !o.contains("class") || !o["class"].is_string() ||
                !o.contains("session") || !o["session"].is_number_integer())
                throw io::FormatError(where +
                                      "needs 'class' (a string) and 'session' (an integer)");
            const std::string cls = o["class"].get<std::string>();
            if (cls != "chair" && cls != "table") continue;  // unknown objects teach nothing
            zones::SessionObject s;
            s.place = place;
            s.session = o["session"].get<int>();
            s.cls = cls == "chair" ? ObjectClass::kChair : ObjectClass::kTable;
            try {
                s.box_world =
                    io::box_from_json(o.contains("box_world") ? o["box_world"] : io::Json());
            } catch (const io::FormatError& e) {
                throw io::FormatError(where + "box_world: " + e.what());
            }
            // A CAD fit fixes the facing; a PCA box may face either way.
            s.facing_known = o.value("class_source", std::string()) == "cad" &&
                             !o.value("model", std::string()).empty();
            out.push_back(s);
        }
    } catch (const io::FormatError& e) {
        throw io::FileError(path.string(), e.what());
    } catch (const io::Json::exception& e) {
        throw io::FileError(path.string(), e.what());
    }
    return out;
}

// The object map of one `makeway run` output (objects/NNNNNN.json per keyframe), as place
// `place`: objects at least `min_existence` likely.
std::vector<zones::TrackedObject> read_tracked_objects(const fs::path& folder, int place,
                                                       double min_existence) {
    std::vector<zones::TrackedObject> out;
    for (const fs::path& path : io::frame_files(folder / "objects", "json")) {
        double stamp = 0.0;
        for (const ObjectEstimate& o : io::read_object_frame(path, &stamp)) {
            if (o.existence >= min_existence)
                out.push_back({place, o.id, stamp, o.cls, o.box_world});
        }
    }
    return out;
}

}  // namespace

struct LearnZonesOptions {
    std::vector<std::string> labels, tracks;
    double track_gap_s = 5.0, min_existence = 0.5;
    std::string out, png;
    zones::ZoneLearnParams params;
    bool no_png = false;
};

int run_learn_zones(const LearnZonesOptions& o) {
    if (o.labels.empty() && o.tracks.empty()) {
        print_error("learn-zones: give --labels DIR... and/or --tracks DIR...");
        return kExitBadInput;
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<zones::SessionObject> objects;
    for (std::size_t i = 0; i < o.labels.size(); ++i) {
        const auto more = read_labelled_objects(o.labels[i], static_cast<int>(i));
        objects.insert(objects.end(), more.begin(), more.end());
    }
    std::vector<zones::TrackedObject> tracked;
    for (std::size_t i = 0; i < o.tracks.size(); ++i) {
        const auto more = read_tracked_objects(o.tracks[i], static_cast<int>(i), o.min_existence);
        tracked.insert(tracked.end(), more.begin(), more.end());
    }
    const zones::ZoneLearning l =
        zones::learn_zones(objects, o.params, zones::track_motions(tracked, o.track_gap_s));
    std::string header = "makeway learned affordance zones (makeway learn-zones) from " +
                         std::to_string(o.labels.size()) + " labelled place(s) and " +
                         std::to_string(o.tracks.size()) + " tracked drive(s):\n";
    for (const std::string& d : o.labels)
        header += "  labels " + fs::path(d).filename().string() + "\n";
    for (const std::string& d : o.tracks)
        header += "  tracks " + fs::path(d).filename().string() + "\n";
    char line[256];
    for (const ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        const zones::ClassLearning& c = cls == ObjectClass::kChair ? l.chair : l.table;
        std::snprintf(line, sizeof line,
                      "%s: %zu observations, %zu motions (both directions of each match; %zu "
                      "within tracks), mean match confidence %.2f, %.0f %% moved; %zu never "
                      "matched, %zu unsure, %zu without a facing\n",
                      std::string(to_string(cls)).c_str(), c.observations, c.motions, c.tracked,
                      c.mean_confidence, 100.0 * c.moved_share, c.unmatched, c.unsure,
                      c.facing_unknown);
        header += line;
    }
    io::write_zones(o.out, l.zones, header);
    const fs::path png =
        o.png.empty() ? fs::path(o.out).replace_extension(".png") : fs::path(o.png);
    if (!o.no_png) io::write_zones_png(png, l.zones, io::Config{}.affordance);
    std::cout << header;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %s%s in %.1f s\n", o.out.c_str(),
                o.no_png ? "" : (" and " + png.string()).c_str(), s);
    return 0;
}

struct BenchZonesOptions {
    eval::ZoneBenchParams params;
    std::string usage = "pulled_back";
    std::string source = "truth";
    std::string out = "out/bench_zones";
};

namespace {

io::Json coverage_json(const eval::ZoneCoverage& c) {
    return {
        {"objects", c.objects},
        {"truth_cells", c.truth_cells},
        {"hand_drawn", c.hand_drawn()},
        {"learned_equal_area", c.learned_equal_area()},
        {"learned", c.learned()},
        {"ratio_equal_area", c.hand_drawn() > 0 ? c.learned_equal_area() / c.hand_drawn() : 0.0},
        {"hand_drawn_area_m2_per_zone",
         c.objects ? c.hand_drawn_area / static_cast<double>(c.objects) : 0.0},
        {"learned_area_m2_per_zone",
         c.objects ? c.learned_area / static_cast<double>(c.objects) : 0.0}};
}

std::string coverage_row(const std::string& what, const eval::ZoneCoverage& c, double cell_m2) {
    if (c.objects == 0) return "| " + what + " | 0 | - | - | - | - | - | - | - |\n";
    char miss[32] = "-";  // nothing missed by the hand-drawn zones: no ratio
    const double miss_hand = 1.0 - c.hand_drawn(), miss_learned = 1.0 - c.learned_equal_area();
    if (miss_hand > 1e-9) std::snprintf(miss, sizeof miss, "%.2f", miss_learned / miss_hand);
    char line[320];
    std::snprintf(line, sizeof line,
                  "| %s | %zu | %.3f | %.3f | %.2fx | %s | %.3f | %.2f | %.2f |\n", what.c_str(),
                  c.objects, c.hand_drawn(), c.learned_equal_area(),
                  c.learned_equal_area() / c.hand_drawn(), miss, c.learned(),
                  cell_m2 * c.hand_drawn_area / static_cast<double>(c.objects),
                  cell_m2 * c.learned_area / static_cast<double>(c.objects));
    return line;
}

}  // namespace

int run_bench_zones(const BenchZonesOptions& o) {
    eval::ZoneBenchParams p = o.params;
    p.usage = *sim::parse_usage_profile(o.usage);
    p.source = o.source == "labels" ? eval::ZoneSource::kLabels : eval::ZoneSource::kTruth;
    p.hand_drawn = io::Config{}.affordance;
    io::ProgressBar bar("bench zones", static_cast<std::size_t>(p.scenes));
    const auto t0 = std::chrono::steady_clock::now();
    const eval::ZoneBenchResult r =
        eval::run_zone_bench(p, [&](std::size_t done, std::size_t) { bar.update(done); });
    bar.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Cell counts are per cell_m^2; the JSON's areas are in m^2 per zone placed.
    const double cell_m2 = p.cell_m * p.cell_m;
    io::Json scenes = io::Json::array();
    for (const eval::ZoneBenchScene& s : r.scenes) {
        scenes.push_back({{"name", s.name},
                          {"chair", coverage_json(s.chair)},
                          {"table", coverage_json(s.table)},
                          {"chair_moved", coverage_json(s.chair_moved)},
                          {"table_moved", coverage_json(s.table_moved)},
                          {"chair_motions", s.chair_learning.motions},
                          {"chair_mean_match_confidence", s.chair_learning.mean_confidence},
                          {"table_motions", s.table_learning.motions},
                          {"table_mean_match_confidence", s.table_learning.mean_confidence},
                          {"learn_seconds", s.learn_seconds},
                          {"label_seconds", s.label_seconds}});
    }
    const auto scale_areas = [&](io::Json j) {
        j["hand_drawn_area_m2_per_zone"] = j["hand_drawn_area_m2_per_zone"].get<double>() * cell_m2;
        j["learned_area_m2_per_zone"] = j["learned_area_m2_per_zone"].get<double>() * cell_m2;
        return j;
    };
    for (io::Json& s : scenes)
        for (const char* k : {"chair", "table", "chair_moved", "table_moved"})
            s[k] = scale_areas(s[k]);
    const io::Json j = {{"usage", o.usage},
                        {"source", o.source},
                        {"scenes", p.scenes},
                        {"seed", p.seed},
                        {"train_sessions", p.train_sessions},
                        {"test_sessions", p.test_sessions},
                        {"coverage_threshold", p.learn.zone.coverage_threshold},
                        {"prior_strength", p.learn.zone.prior_strength},
                        {"chair", scale_areas(coverage_json(r.total.chair))},
                        {"table", scale_areas(coverage_json(r.total.table))},
                        {"chair_moved", scale_areas(coverage_json(r.total.chair_moved))},
                        {"table_moved", scale_areas(coverage_json(r.total.table_moved))},
                        {"learn_seconds", r.total.learn_seconds},
                        {"label_seconds", r.total.label_seconds},
                        {"seconds", seconds},
                        {"per_scene", scenes}};
    std::string table =
        "# Learned vs hand-drawn affordance zones: usage " + o.usage + ", " +
        std::to_string(p.scenes) + " scenes, seed " + std::to_string(p.seed) + ", learned from " +
        std::to_string(p.train_sessions) + " sessions, scored on the next " +
        std::to_string(p.test_sessions) + " (" +
        (o.source == "labels" ? "auto-labelled drives" : "the sessions' boxes, identities hidden") +
        ")\n\nCoverage: the share of an object's footprint cells in the later sessions inside the "
        "zone placed where it stood in the last learned session (footprints scored: objects x "
        "later sessions). Learned (equal area): the learned zone cut to the hand-drawn zone's "
        "area; missed: the footprint cells outside the zone. Areas: per zone placed.\n\n"
        "| objects | footprints scored | hand-drawn | learned (equal area) | ratio | missed, "
        "learned / hand-drawn | learned (own threshold) | hand-drawn area [m^2] | learned area "
        "[m^2] |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    table += coverage_row("chairs", r.total.chair, cell_m2);
    table += coverage_row("tables", r.total.table, cell_m2);
    table += coverage_row("chairs that moved", r.total.chair_moved, cell_m2);
    table += coverage_row("tables that moved", r.total.table_moved, cell_m2);
    io::StagedOutput staged(o.out);
    const fs::path out = staged.staging();
    io::write_json(out / "summary.json", j);
    io::write_file_atomic(out / "table.md", table);
    io::write_zones(out / "zones.yaml", r.pooled,
                    "learned by makeway bench zones (usage " + o.usage + ") from " +
                        std::to_string(p.train_sessions) + " sessions of each of " +
                        std::to_string(p.scenes) + " scenes");
    io::write_zones_png(out / "zones.png", r.pooled, p.hand_drawn);
    staged.commit();
    std::cout << table;
    std::printf("learning: %.2f s over %d scenes; all: %.1f s; wrote %s\n", r.total.learn_seconds,
                p.scenes, seconds, o.out.c_str());
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_learn_zones(CommandSpec& c, LearnZonesOptions& o) {
    c.option("--labels", o.labels,
             "makeway label outputs (objects.json: every object of every session of one place); "
             "sessions are compared within a folder, never across")
        .expected(1, -1);
    c.option("--tracks", o.tracks,
             "makeway run outputs (objects/ per keyframe): the object map's tracks, each sampled "
             "every --track-gap-s, its motion between samples (chairs pushed and pulled while the "
             "robot watched)")
        .expected(1, -1);
    c.option("--track-gap-s", o.track_gap_s, "Seconds between a track's samples")
        .range(0.1, 3600.0)
        .show_default();
    c.option("--min-existence", o.min_existence, "Tracked objects less likely are left out")
        .range(0.0, 1.0)
        .show_default();
    c.option("--out", o.out, "Zones file to write (YAML; the affordance layer's `--zones`)")
        .required();
    c.option("--png", o.png, "Picture of the zones (default: the zones file with .png)").output();
    c.flag("--no-png", o.no_png, "Write no picture");
    c.option("--match-gate-m", o.params.match_gate_m,
             "Objects of two sessions farther apart are not the same object")
        .range(0.01, 5.0)
        .show_default();
    c.option("--min-confidence", o.params.min_match_confidence,
             "Matches less sure than this are left out (1 - d / d_next)")
        .range(0.0, 1.0)
        .show_default();
    c.option("--kernel-m", o.params.zone.kernel_m, "Smoothing of the footprint's edges")
        .range(0.001, 0.2)
        .show_default();
    c.option("--coverage-threshold", o.params.zone.coverage_threshold,
             "The zone: where the footprint goes at least this often")
        .range(0.001, 0.999)
        .show_default();
    c.option("--prior-strength", o.params.zone.prior_strength,
             "Pseudo-observations of the hand-drawn zone blended in (0: the data alone)")
        .range(0.0, 1e6)
        .show_default();
}
const Registration<LearnZonesOptions> kLearnZones{
    "learn-zones", Group::kLearning,
    "Affordance zones learned from how this building's furniture moved between labelled "
    "sessions (objects matched across sessions, motions in each object's frame, a density "
    "over where its footprint goes, the hand-drawn zone as the prior): zones.yaml and zones.png",
    declare_learn_zones, run_learn_zones};

void declare_bench_zones(CommandSpec& c, BenchZonesOptions& o) {
    c.option("--scenes", o.params.scenes, "Buildings (generated; medium and dense alternate)")
        .range(1, 10000)
        .show_default();
    c.option("--seed", o.params.seed, "Seed of the first scene (scene i: seed + i)").show_default();
    c.option("--source", o.source,
             "What the zones are learned from: truth (the sessions' boxes, identities hidden) or "
             "labels (each training session driven and auto-labelled with the scene's CAD "
             "models, as makeway label does: minutes per scene)")
        .choices({"truth", "labels"})
        .show_default();
    c.option("--track-gap-s", o.params.track_gap_s,
             "With --source truth: also learn from each training session's objects tracked over "
             "its first minute (the chair pushers at work), sampled every this many seconds, as "
             "learn-zones --tracks does (0: sessions alone)")
        .range(0.0, 60.0)
        .show_default();
    c.option("--max-sweeps", o.params.max_sweeps, "Sweeps per labelled session at most")
        .range(10, 100000)
        .show_default();
    c.option("--usage", o.usage, "How the scenes' people move the furniture between sessions")
        .choices(sim::usage_profile_names())
        .show_default();
    c.option("--train-sessions", o.params.train_sessions, "Sessions learned from (K)")
        .range(2, 100)
        .show_default();
    c.option("--test-sessions", o.params.test_sessions, "Later sessions predicted (M)")
        .range(1, 100)
        .show_default();
    c.option("--coverage-threshold", o.params.learn.zone.coverage_threshold,
             "The learned zone: where the footprint goes at least this often")
        .range(0.001, 0.999)
        .show_default();
    c.option("--prior-strength", o.params.learn.zone.prior_strength,
             "Pseudo-observations of the hand-drawn zone")
        .range(0.0, 1e6)
        .show_default();
    c.option("--out", o.out,
             "Output folder: summary.json, table.md, zones.yaml and zones.png (learned from every "
             "scene's sessions)")
        .show_default();
}
const Registration<BenchZonesOptions> kBenchZones{
    "bench zones", Group::kEvaluation,
    "Learned affordance zones against the hand-drawn ones: learn from K sessions of each "
    "building, score on the next M where the furniture went (coverage at equal area)",
    declare_bench_zones, run_bench_zones};

}  // namespace

}  // namespace makeway::apps
