// makeway eval-tracking (CLEAR MOT and HOTA; the KITTI protocol as AB3DMOT reports it) and
// bench track (the tracker on simulated drives).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>

#include "apps/command.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "io/tracking_io.hpp"
#include "makeway/eval/kitti_tracking_eval.hpp"
#include "makeway/eval/track_bench.hpp"

namespace makeway::apps {

struct EvalTrackingOptions {
    std::string gt;
    std::string tracks;
    std::string format = "makeway";
    std::vector<std::string> classes;  ///< kitti: classes evaluated (default: those in the tracks)
    double min_iou = 0.25;             ///< kitti: 3D IoU of a match
    double fov_deg = 0.0;              ///< kitti: > 0 scores only this horizontal field of view
    bool devkit_rounding = false;      ///< kitti: AB3DMOT's script's re-averaged scores, to the bit
    std::string out;                   ///< optional JSON
};

struct BenchTrackOptions {
    std::string config;  ///< YAML whose tracking section replaces the defaults (empty: none)
    bool scan_occlusion = false;
    int scenes = 5;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_track";
};

namespace fs = std::filesystem;
using io::to_lower;

namespace {

// A KITTI file as the evaluation's boxes, per frame (types lower case, as the devkit compares).
eval::KittiSequence kitti_boxes(const fs::path& file, bool tracker) {
    eval::KittiSequence seq;
    std::set<std::pair<int, int>> seen;
    for (const auto& r : io::read_kitti_tracking(file)) {
        if (seq.size() <= static_cast<std::size_t>(r.frame))
            seq.resize(static_cast<std::size_t>(r.frame) + 1);
        eval::KittiBox b;
        b.track_id = r.track_id;
        b.type = to_lower(r.type);
        b.truncation = static_cast<int>(r.truncated);
        b.occlusion = static_cast<int>(r.occluded);
        b.bbox_px = r.bbox_px;
        if (!r.is_dont_care()) b.box = io::box_from_kitti(r);
        b.score = r.score.value_or(-1.0);  // the devkit's value for a missing score
        if (tracker && !r.is_dont_care()) {
            if (r.track_id < 0)
                throw io::FileError(file.string(), "frame " + std::to_string(r.frame) +
                                                       ": a track line without a track id");
            if (!seen.insert({r.frame, r.track_id}).second) {
                throw io::FileError(file.string(), "frame " + std::to_string(r.frame) +
                                                       ": track id " + std::to_string(r.track_id) +
                                                       " twice");
            }
        }
        seq[static_cast<std::size_t>(r.frame)].push_back(b);
    }
    return seq;
}

io::Json kitti_clear_json(const eval::KittiClear& m) {
    return {{"threshold", m.threshold},
            {"recall_target", m.recall_target},
            {"mota", m.mota},
            {"motp", m.motp},
            {"moda", m.moda},
            {"smota", m.smota},
            {"recall", m.recall},
            {"precision", m.precision},
            {"f1", m.f1},
            {"mt", m.mostly_tracked},
            {"pt", m.partly_tracked},
            {"ml", m.mostly_lost},
            {"tp", m.tp},
            {"fp", m.fp},
            {"fn", m.fn},
            {"ignored_tp", m.ignored_tp},
            {"ignored_fn", m.ignored_fn},
            {"ignored_tracker", m.ignored_tracker},
            {"id_switches", m.id_switches},
            {"fragmentations", m.fragmentations},
            {"gt", m.gt}};
}

int run_eval_tracking_kitti(const EvalTrackingOptions& o) {
    std::vector<eval::KittiSequence> gt, tracks;
    for (const auto& g : io::kitti_sequence_files(o.gt)) {
        const fs::path t =
            fs::is_regular_file(o.tracks) ? fs::path(o.tracks) : fs::path(o.tracks) / g.filename();
        if (!fs::exists(t))
            throw io::FileError(t.string(),
                                "no tracks for ground-truth sequence " + g.filename().string());
        gt.push_back(kitti_boxes(g, false));
        tracks.push_back(kitti_boxes(t, true));
    }
    std::vector<std::string> classes;
    for (const std::string& c : o.classes) classes.push_back(to_lower(c));
    if (classes.empty()) {  // those in the tracks; a neighbouring class is scored with its main one
        std::set<std::string> present;
        for (const auto& seq : tracks)
            for (const auto& f : seq)
                for (const auto& b : f) present.insert(b.type);
        for (const std::string& c : present) {
            if ((c == "van" && present.count("car")) ||
                (c == "person_sitting" && present.count("pedestrian")) || c == "dontcare")
                continue;
            classes.push_back(c);
        }
    }
    io::Json j;
    std::cout << "| class | sAMOTA | AMOTA | AMOTP | MOTA | MOTP | IDS | FRAG | MT | ML | TP | FP "
                 "| FN | GT boxes |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& c : classes) {
        eval::KittiEvalParams p;
        p.cls = c;
        p.min_iou_3d = o.min_iou;
        p.fov_deg = o.fov_deg;
        p.devkit_rounding = o.devkit_rounding;
        const eval::KittiEvalResult r = eval::evaluate_kitti(gt, tracks, p);
        const eval::KittiClear& b = r.best;
        std::cout << std::fixed << std::setprecision(4) << "| " << c << " | " << r.samota << " | "
                  << r.amota << " | " << r.amotp << " | " << b.mota << " | " << b.motp << " | "
                  << b.id_switches << " | " << b.fragmentations << " | " << b.mostly_tracked
                  << " | " << b.mostly_lost << " | " << b.tp << " | " << b.fp << " | " << b.fn
                  << " | " << r.gt_boxes << " |\n";
        io::Json curve = io::Json::array();
        for (const auto& m : r.curve) curve.push_back(kitti_clear_json(m));
        j["classes"][c] = {{"samota", r.samota},
                           {"amota", r.amota},
                           {"amotp", r.amotp},
                           {"best_threshold", kitti_clear_json(b)},
                           {"all_boxes", kitti_clear_json(r.all)},
                           {"curve", curve},
                           {"gt_boxes", r.gt_boxes},
                           {"tracker_boxes", r.tracker_boxes}};
    }
    std::cout << "MOTA..FN at the score threshold of best MOTA; 3D IoU >= " << o.min_iou
              << (o.fov_deg > 0
                      ? ", field of view " + std::to_string(o.fov_deg).substr(0, 5) + " deg"
                      : std::string())
              << (o.devkit_rounding
                      ? "; AB3DMOT's evaluate.py's re-averaged scores (--devkit-rounding)"
                      : "")
              << "\n";
    if (!o.out.empty()) {
        j["protocol"] = {{"min_iou_3d", o.min_iou},
                         {"fov_deg", o.fov_deg},
                         {"recall_steps", 40},
                         {"max_truncation", 0},
                         {"max_occlusion", 2},
                         {"min_height_px", 25},
                         {"devkit_rounding", o.devkit_rounding}};
        io::write_json(o.out, j);
    }
    return 0;
}

io::Json metrics_json(const eval::TrackingMetrics& m) {
    return {{"mota", m.clear.mota},
            {"motp", m.clear.motp},
            {"id_switches", m.clear.id_switches},
            {"fragmentations", m.clear.fragmentations},
            {"tp", m.clear.tp},
            {"fp", m.clear.fp},
            {"fn", m.clear.fn},
            {"gt", m.clear.gt},
            {"hota", m.hota.hota},
            {"deta", m.hota.deta},
            {"assa", m.hota.assa}};
}

void print_table(const eval::TrackingMetrics& all,
                 const std::map<ObjectClass, eval::TrackingMetrics>& per) {
    std::cout << "| class | HOTA | DetA | AssA | MOTA | MOTP | ID switches | fragmentations | GT "
                 "|\n|---|---|---|---|---|---|---|---|---|\n";
    auto row = [](const std::string& name, const eval::TrackingMetrics& m) {
        std::cout << std::fixed << std::setprecision(3) << "| " << name << " | " << m.hota.hota
                  << " | " << m.hota.deta << " | " << m.hota.assa << " | " << m.clear.mota << " | "
                  << m.clear.motp << " | " << m.clear.id_switches << " | " << m.clear.fragmentations
                  << " | " << m.clear.gt << " |\n";
    };
    for (const auto& [cls, m] : per) row(std::string(to_string(cls)), m);
    row("all", all);
}

}  // namespace

int run_eval_tracking(const EvalTrackingOptions& o) {
    if (o.format == "kitti") return run_eval_tracking_kitti(o);
    std::vector<eval::TrackingFrame> gt, tracks;
    auto json_frames = [](const std::string& dir) {
        std::vector<fs::path> out;
        for (const auto& f : io::frame_files(dir, "json")) {
            if (f.filename() != "summary.json") out.push_back(f);
        }
        return out;
    };
    const auto gt_files = json_frames(o.gt);
    const auto tr_files = json_frames(o.tracks);
    if (gt_files.size() != tr_files.size()) {
        throw io::FileError(o.tracks, "holds " + std::to_string(tr_files.size()) +
                                          " frames, the ground truth " +
                                          std::to_string(gt_files.size()));
    }
    auto frame = [](const fs::path& f) {
        eval::TrackingFrame out;
        for (const ObjectEstimate& e : io::read_object_frame(f))
            out.push_back({e.id, e.cls, e.box_world});
        return out;
    };
    for (std::size_t k = 0; k < gt_files.size(); ++k)
        gt.push_back(frame(gt_files[k])), tracks.push_back(frame(tr_files[k]));
    const auto all = eval::evaluate_tracking(gt, tracks);
    const auto per = eval::evaluate_tracking_per_class(gt, tracks);
    print_table(all, per);
    if (!o.out.empty()) {
        io::Json j = metrics_json(all);
        for (const auto& [cls, m] : per)
            j["per_class"][std::string(to_string(cls))] = metrics_json(m);
        io::write_json(o.out, j);
    }
    return 0;
}

int run_bench_track(const BenchTrackOptions& o) {
    eval::TrackBenchParams p;
    p.scenes = o.scenes;
    p.seed = o.seed;
    p.use_scan_occlusion = o.scan_occlusion;
    if (!o.config.empty()) p.tracker = io::load_config(o.config).system.tracker;
    io::ProgressBar bar("bench track", static_cast<std::size_t>(p.scenes));
    const eval::TrackBenchResult r = eval::run_track_bench(
        p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    io::Json j = metrics_json(r.overall);
    j["fps"] = r.fps;
    j["frames"] = r.frames;
    j["scenes"] = p.scenes;
    j["seed"] = p.seed;
    j["mean_detections_per_frame"] = r.mean_detections_per_frame;
    j["scan_occlusion"] = p.use_scan_occlusion;
    if (!o.config.empty()) j["config"] = o.config;
    j["yaw_within_10deg_detections"] = r.yaw_within_10deg_detections;
    j["yaw_within_10deg_map"] = r.yaw_within_10deg_map;
    j["occlusion_gaps_up_to_2s"] = r.occlusion_gaps;
    j["occlusion_gaps_kept_id"] = r.occlusion_gaps_kept;
    j["false_positives"] = r.false_positives;
    j["false_positive_track_frames_in_map"] = r.false_positive_tracks_output;
    j["false_positive_tracks_after_3_frames"] = r.false_positive_tracks_lingering;
    j["map_sanity"] = {{"object_frames", r.map_sanity.object_frames},
                       {"outside_room", r.map_sanity.outside_room},
                       {"above_floor_0_3m", r.map_sanity.above_floor},
                       {"fast_unpushed_0_5mps", r.map_sanity.fast_unpushed},
                       {"max_speed_mps", r.map_sanity.max_speed_mps},
                       {"max_bottom_m", r.map_sanity.max_bottom_m}};
    j["rates"] = {{"miss", p.p_miss},
                  {"false_positive", p.false_positive_rate},
                  {"flip_90_each", p.p_flip_90},
                  {"flip_180", p.p_flip_180}};
    for (const auto& [cls, m] : r.per_class)
        j["per_class"][std::string(to_string(cls))] = metrics_json(m);
    fs::create_directories(o.out_dir);
    io::write_json(fs::path(o.out_dir) / "summary.json", j);
    print_table(r.overall, r.per_class);
    std::cout << "map objects outside the room " << r.map_sanity.outside_room
              << ", above the floor " << r.map_sanity.above_floor << ", fast and not pushed "
              << r.map_sanity.fast_unpushed << " (of " << r.map_sanity.object_frames
              << " object-frames)\n";
    std::cout << std::setprecision(1) << "fps " << r.fps << ", yaw within 10 deg: detections "
              << 100 * r.yaw_within_10deg_detections << " %, map " << 100 * r.yaw_within_10deg_map
              << " %; wrote " << (fs::path(o.out_dir) / "summary.json").string() << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_eval_tracking(CommandSpec& c, EvalTrackingOptions& e) {
    c.option("--gt", e.gt,
             "Ground truth: folder of per-frame object JSON (as makeway simulate writes), or KITTI")
        .required();
    c.option("--tracks", e.tracks, "Tracks in the same format").required();
    c.option("--format", e.format, "makeway or kitti").choices({"makeway", "kitti"}).show_default();
    c.option("--classes", e.classes,
             "kitti: classes to evaluate, comma separated (default: those in the tracks)")
        .delimiter(',');
    c.option("--iou", e.min_iou, "kitti: 3D IoU a match needs").range(0.01, 1.0).show_default();
    c.option("--fov-deg", e.fov_deg,
             "kitti: score only boxes within this horizontal field of view (0: all)")
        .range(0.0, 360.0);
    c.flag("--devkit-rounding", e.devkit_rounding,
           "kitti: AB3DMOT's evaluate.py's score handling, to the bit: it averages "
           "each track's already averaged scores again at every threshold (a "
           "track can drop out an ulp under its own score); off: one mean per track");
    c.option("--out", e.out, "Also write the metrics as JSON");
}
const Registration<EvalTrackingOptions> kEvalTracking{
    "eval-tracking", Group::kEvaluation,
    "Tracking metrics. makeway format: CLEAR MOT (MOTA, MOTP, ID switches, fragmentations) and "
    "HOTA (DetA, AssA) per class, 3D IoU; kitti: the KITTI protocol as "
    "AB3DMOT reports it (sAMOTA, AMOTA, AMOTP; DontCare, neighbouring classes)",
    declare_eval_tracking, run_eval_tracking};

void declare_bench_track(CommandSpec& c, BenchTrackOptions& trk_o) {
    c.option("--scenes", trk_o.scenes, "Scenes (alternating medium and dense)")
        .range(1, 1000)
        .show_default();
    c.option("--seed", trk_o.seed, "Seed of scenes and corruption").show_default();
    c.option("--config", trk_o.config,
             "YAML configuration: its tracking section replaces the defaults");
    c.option("--out", trk_o.out_dir, "Output folder (summary.json)").show_default();
    c.flag("--scan-occlusion", trk_o.scan_occlusion,
           "Also treat LiDAR returns in front of an object as occlusion "
           "(walls, people), beyond the paper's object boxes");
}
const Registration<BenchTrackOptions> kBenchTrack{
    "bench track", Group::kEvaluation,
    "Tracking on simulated drives: visible objects' ground truth corrupted "
    "(20 % missed, 10 % false positives, noise, yaw flips); MOTA, HOTA, "
    "map yaw accuracy, frames per second",
    declare_bench_track, run_bench_track};

}  // namespace

}  // namespace makeway::apps
