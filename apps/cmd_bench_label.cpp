// `makeway bench label` (the automatic annotation against the simulator's truth) and `makeway
// bench sessions` (a detector fine-tuned on auto-labels, session after session).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "makeway/eval/label_bench.hpp"
#include "makeway/eval/session_bench.hpp"
#include "makeway/sim/furniture.hpp"

namespace makeway::apps {

struct BenchSessionsOptions {
    std::string model;  ///< the detector to start from (default weights when empty)
    /// The benchmark's parameters, filled by the options directly; the command line fine-tunes
    /// for 6 epochs on 2 threads (inference runs on as many).
    eval::SessionBenchParams params = [] {
        eval::SessionBenchParams p;
        p.train.epochs = 6;
        p.train.threads = 2;
        return p;
    }();
    std::string out_dir = "out/bench_sessions";
};

struct BenchLabelOptions {
    eval::LabelBenchParams params;  ///< filled by the options directly (`cad` by --no-cad)
    bool no_cad = false;
    std::string out_dir = "out/bench_label";
};

namespace fs = std::filesystem;
namespace {

io::Json label_metrics_json(const eval::DetectionMetrics& m) {
    io::Json j = {
        {"map_25", m.map_25}, {"map_50", m.map_50}, {"mar_25", m.mar_25}, {"mar_50", m.mar_50}};
    io::Json per = io::Json::object();
    for (const auto& [cls, c] : m.per_class) {
        per[std::string(to_string(cls))] = {{"ap_25", c.ap_25},
                                            {"ap_50", c.ap_50},
                                            {"ar_25", c.ar_25},
                                            {"ar_50", c.ar_50},
                                            {"yaw_within_10deg", c.yaw_within_10deg},
                                            {"ground_truth", c.ground_truth},
                                            {"labels", c.detections}};
    }
    j["per_class"] = per;
    return j;
}

io::Json panoptic_json(const eval::PanopticQuality& p) {
    return {{"pq", p.pq()}, {"sq", p.sq()}, {"rq", p.rq()},
            {"tp", p.tp},   {"fp", p.fp},   {"fn", p.fn}};
}

// Yaw within 10 deg over the matched boxes of both classes, weighted by their ground truth.
double yaw_within_10(const eval::DetectionMetrics& m) {
    double sum = 0.0, n = 0.0;
    for (const auto& [cls, c] : m.per_class) {
        sum += c.yaw_within_10deg * static_cast<double>(c.ground_truth);
        n += static_cast<double>(c.ground_truth);
    }
    return n > 0 ? sum / n : 0.0;
}

}  // namespace

int run_bench_label(const BenchLabelOptions& o) {
    eval::LabelBenchParams p = o.params;
    p.cad = !o.no_cad;
    io::ProgressBar bar("bench label", static_cast<std::size_t>(p.scenes));
    const eval::LabelBenchResult r = eval::run_label_bench(
        p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    io::Json scenes = io::Json::array();
    for (const eval::LabelBenchScene& s : r.scenes) {
        const auto iou = eval::class_iou(s.confusion);
        scenes.push_back({{"name", s.name},
                          {"sweeps", s.sweeps},
                          {"keyframes", s.keyframes},
                          {"objects", s.objects},
                          {"cad_objects", s.cad_objects},
                          {"unknown_objects", s.unknown_objects},
                          {"alignment_residual_m", s.alignment_residual_m},
                          {"alignment_correction_m", s.alignment_correction_m},
                          {"iou",
                           {{"ground", iou[0]},
                            {"permanent", iou[1]},
                            {"movable", iou[2]},
                            {"dynamic", iou[3]}}},
                          {"panoptic", panoptic_json(s.panoptic)},
                          {"boxes", label_metrics_json(s.boxes)},
                          {"still_boxes", label_metrics_json(s.still_boxes)},
                          {"iou_by_motion",
                           {{"movable", eval::class_iou(s.confusion_by_motion)[2]},
                            {"dynamic", eval::class_iou(s.confusion_by_motion)[3]}}},
                          {"label_seconds", s.label_seconds}});
    }
    const io::Json j = {{"scenes", p.scenes},
                        {"sessions", p.sessions},
                        {"seed", p.seed},
                        {"cad", p.cad},
                        {"iou",
                         {{"ground", r.iou[0]},
                          {"permanent", r.iou[1]},
                          {"movable", r.iou[2]},
                          {"dynamic", r.iou[3]}}},
                        {"confusion_truth_by_predicted", r.confusion},
                        {"iou_by_motion",
                         {{"ground", r.iou_by_motion[0]},
                          {"permanent", r.iou_by_motion[1]},
                          {"movable", r.iou_by_motion[2]},
                          {"dynamic", r.iou_by_motion[3]}}},
                        {"still_boxes", label_metrics_json(r.still_boxes)},
                        {"still_yaw_within_10deg", yaw_within_10(r.still_boxes)},
                        {"panoptic", panoptic_json(r.panoptic)},
                        {"boxes", label_metrics_json(r.boxes)},
                        {"yaw_within_10deg", yaw_within_10(r.boxes)},
                        {"per_scene", scenes}};
    const fs::path out(o.out_dir);
    io::write_json(out / "summary.json", j);
    std::cout << "point IoU: ground " << r.iou[0] << ", permanent " << r.iou[1] << ", movable "
              << r.iou[2] << ", dynamic " << r.iou[3] << "\ninstances: PQ " << r.panoptic.pq()
              << " (SQ " << r.panoptic.sq() << ", RQ " << r.panoptic.rq() << ")"
              << "\nboxes: AP@0.25 " << r.boxes.map_25 << ", AP@0.5 " << r.boxes.map_50
              << ", yaw within 10 deg " << yaw_within_10(r.boxes)
              << "\nby motion (chairs pulled during a session as dynamic): movable IoU "
              << r.iou_by_motion[2] << ", dynamic IoU " << r.iou_by_motion[3] << ", box AP@0.25 "
              << r.still_boxes.map_25 << ", AP@0.5 " << r.still_boxes.map_50
              << ", yaw within 10 deg " << yaw_within_10(r.still_boxes) << "\nwrote "
              << (out / "summary.json").string() << "\n";
    return 0;
}

int run_bench_sessions(const BenchSessionsOptions& o) {
    const eval::SessionBenchParams& p = o.params;
    for (const std::string& style : p.left_out_styles) {
        if (!sim::parse_furniture_style(style))
            throw std::invalid_argument("--left-out-styles: unknown style '" + style + "'");
    }
    perception::Detector detector = load_detector(o.model);
    perception::set_inference_threads(p.train.threads);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<eval::SessionRound> rounds =
        eval::run_session_bench(detector, p, [&](const std::string& what) {
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("[%6.0f s] %s\n", s, what.c_str());
            std::fflush(stdout);
        });
    const fs::path out(o.out_dir);
    io::Json rows = io::Json::array();
    std::string table =
        "| round | auto-labelled keyframes | labelled objects | left-out mAP@0.25 | left-out "
        "mAP@0.5 | trained styles mAP@0.25 | trained styles mAP@0.5 |\n"
        "| --- | --- | --- | --- | --- | --- | --- |\n";
    char line[256];
    for (const eval::SessionRound& r : rounds) {
        rows.push_back({{"round", r.round},
                        {"labelled_keyframes", r.labelled_keyframes},
                        {"labelled_objects", r.labelled_objects},
                        {"left_out_map_25", r.left_out_map_25},
                        {"left_out_map_50", r.left_out_map_50},
                        {"held_out_map_25", r.held_out_map_25},
                        {"held_out_map_50", r.held_out_map_50},
                        {"label_seconds", r.label_seconds},
                        {"train_seconds", r.train_seconds}});
        std::snprintf(line, sizeof(line), "| %d | %zu | %zu | %.3f | %.3f | %.3f | %.3f |\n",
                      r.round, r.labelled_keyframes, r.labelled_objects, r.left_out_map_25,
                      r.left_out_map_50, r.held_out_map_25, r.held_out_map_50);
        table += line;
    }
    io::write_json(out / "summary.json", {{"left_out_styles", p.left_out_styles},
                                          {"rounds", rows},
                                          {"scenes_per_round", p.scenes_per_round},
                                          {"sessions", p.sessions},
                                          {"epochs", p.train.epochs},
                                          {"replay_scenes", p.replay_scenes},
                                          {"eval_scenes", p.eval_scenes},
                                          {"seed", p.seed}});
    io::write_file_atomic(out / "table.md", table);
    detector.save(out / "model.pt");
    std::cout << table;
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_bench_sessions(CommandSpec& c, BenchSessionsOptions& ses_o) {
    c.option("--model", ses_o.model,
             "Detector to start from (default: models/detector.pt, trained without "
             "armchairs and round tables)");
    c.option("--rounds", ses_o.params.rounds, "Rounds of label + fine-tune")
        .range(1, 20)
        .show_default();
    c.option("--scenes-per-round", ses_o.params.scenes_per_round,
             "Rooms driven and labelled per round")
        .range(1, 100)
        .show_default();
    c.option("--sessions", ses_o.params.sessions, "Sessions per room").range(2, 20).show_default();
    c.option("--max-sweeps", ses_o.params.max_sweeps, "Sweeps per session at most")
        .range(10, 100000)
        .show_default();
    c.option("--epochs", ses_o.params.train.epochs, "Fine-tuning epochs per round")
        .range(1, 1000)
        .show_default();
    c.option("--replay-scenes", ses_o.params.replay_scenes,
             "Simulated scenes of the trained styles replayed in fine-tuning")
        .range(0, 1000)
        .show_default();
    c.option("--eval-scenes", ses_o.params.eval_scenes, "Held-out scenes per scored set")
        .range(1, 100)
        .show_default();
    c.option("--left-out-styles", ses_o.params.left_out_styles, "Styles the detector never saw")
        .delimiter(',')
        .show_default();
    c.option("--threads", ses_o.params.train.threads, "Torch threads").range(1, 256).show_default();
    c.option("--seed", ses_o.params.seed, "Seed of rooms, replay data and fine-tuning")
        .show_default();
    c.option("--out", ses_o.out_dir,
             "Output folder (summary.json, table.md, model.pt: the fine-tuned detector)")
        .show_default();
}
const Registration<BenchSessionsOptions> kBenchSessions{
    "bench sessions", Group::kEvaluation,
    "Session after session: a detector trained without some styles is fine-tuned "
    "on auto-labels of multi-session drives of rooms furnished with them; the "
    "left-out and trained styles' mAP after each round",
    declare_bench_sessions, run_bench_sessions};

void declare_bench_label(CommandSpec& c, BenchLabelOptions& lab_o) {
    c.option("--scenes", lab_o.params.scenes, "Scenes (alternating medium and dense)")
        .range(1, 1000)
        .show_default();
    c.option("--sessions", lab_o.params.sessions, "Sessions per scene").range(2, 20).show_default();
    c.option("--seed", lab_o.params.seed, "Seed of scenes, sessions, sensor noise and wheel drift")
        .show_default();
    c.option("--max-sweeps", lab_o.params.max_sweeps, "Sweeps per session at most (10 per second)")
        .range(10, 100000)
        .show_default();
    c.flag("--no-cad", lab_o.no_cad,
           "Without CAD models: every object keeps its PCA box, unknown class");
    c.option("--out", lab_o.out_dir, "Output folder (summary.json)").show_default();
}
const Registration<BenchLabelOptions> kBenchLabel{
    "bench label", Group::kEvaluation,
    "The automatic annotation against the simulator's truth: multi-session "
    "drives (furniture moved between sessions), point-class IoU, panoptic "
    "quality, box AP@0.25/0.5 and yaw within 10 deg of the auto-labels",
    declare_bench_label, run_bench_label};

}  // namespace

}  // namespace makeway::apps
