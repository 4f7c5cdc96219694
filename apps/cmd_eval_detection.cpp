// makeway eval-detection: the detector, verification and tracking scored on held-out simulated
// rooms, styles left out of training, real furniture models left out of training and rooms of
// clutter alone.
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "apps/command.hpp"
#include "apps/detector_options.hpp"
#include "apps/model_path.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "makeway/eval/detection_eval.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/shape/learned_prior.hpp"

namespace makeway::apps {

struct EvalDetectionOptions {
    std::string model;
    int scenes = 6;
    int max_keyframes = 60;  ///< per scene (a quick look: fewer)
    std::uint64_t seed = 1000000;
    std::string out_dir = "out/eval_detection";
    bool default_cad =
        false;            ///< verify against default-dimension models instead of the scene's own
    bool no_cad = false;  ///< no CAD models at all
    std::string shape_model;     ///< learned shapes for what no CAD model fits
    double shape_e_max = 0.035;  ///< verification's residual bound for completed shapes [m]
    std::string config;          ///< the online system's sections (front end, verification, ...)
    std::string furniture;       ///< real models: the held-out part makes a third set
    int furniture_holdout_every = 3;  ///< eval::split_furniture, as the training used
    int clutter = 8;                  ///< clutter items per room of the fourth set (0: none)
    std::string beam_pattern = "vlp32c";
    double sensor_height = 0.45;
    std::string cad_fit = "exact";  ///< the scene's own models, or approximations of them
};

namespace {

namespace fs = std::filesystem;

io::Json metrics_json(const eval::DetectionMetrics& m) {
    io::Json j = {
        {"map_25", m.map_25}, {"map_50", m.map_50}, {"mar_25", m.mar_25}, {"mar_50", m.mar_50}};
    for (const auto& [cls, c] : m.per_class) {
        j["per_class"][std::string(to_string(cls))] = {{"ap_25", c.ap_25},
                                                       {"ap_50", c.ap_50},
                                                       {"ar_25", c.ar_25},
                                                       {"ar_50", c.ar_50},
                                                       {"yaw_within_10deg", c.yaw_within_10deg},
                                                       {"yaw_within_30deg", c.yaw_within_30deg},
                                                       {"ground_truth", c.ground_truth},
                                                       {"detections", c.detections}};
    }
    return j;
}

int run_eval_detection(const EvalDetectionOptions& o) {
    const perception::Detector detector = load_detector(o.model);
    eval::DetectionEvalParams p;
    p.system = io::load_config(o.config).system;
    p.scenes = o.scenes;
    p.max_keyframes_per_scene = o.max_keyframes;
    p.seed = o.seed;
    p.cad = o.no_cad        ? eval::CadSource::kNone
            : o.default_cad ? eval::CadSource::kDefault
                            : eval::CadSource::kScene;
    std::unique_ptr<shape::LearnedShapePrior> prior;
    if (!o.shape_model.empty()) {
        prior = std::make_unique<shape::LearnedShapePrior>(
            std::make_shared<const shape::ShapeModel>(load_shape_model(o.shape_model)));
        p.shape_prior = prior.get();
        shape::set_threads(1);  // verification runs detections on parallel threads instead
        p.system.verify.shape_e_max_m = o.shape_e_max;
    }
    p.real_held_out = read_furniture_split(o.furniture, o.furniture_holdout_every).held_out;
    if (!o.furniture.empty() && p.real_held_out.empty())
        throw io::FileError(o.furniture,
                            "no model is held out of training (too few models for "
                            "--furniture-holdout-every " +
                                std::to_string(o.furniture_holdout_every) + ")");
    p.clutter.count = o.clutter;
    p.beam_pattern = *sim::parse_beam_pattern(o.beam_pattern);
    p.sensor_height_m = o.sensor_height;
    p.cad_fit = *eval::parse_cad_fit(o.cad_fit);
    const int sets = 2 + (p.real_held_out.empty() ? 0 : 1) + (o.clutter > 0 ? 1 : 0);
    io::ProgressBar bar("eval-detection", static_cast<std::size_t>(sets * o.scenes));
    int arm = 0;
    std::string last;
    const auto r = eval::run_detection_eval(detector, p, [&](const std::string& what, int d, int) {
        if (what != last) last = what, ++arm;
        bar.update(static_cast<std::size_t>((arm - 1) * o.scenes + d));
    });
    bar.finish();
    auto stages = [](const eval::StageMetrics& m) {
        return io::Json{{"network", metrics_json(m.network)},
                        {"verified", metrics_json(m.verified)},
                        {"tracked", metrics_json(m.tracked)}};
    };
    io::Json j = metrics_json(r.held_out.network);
    j["stages"] = stages(r.held_out);
    j["left_out"] = metrics_json(r.left_out.network);
    j["left_out"]["styles"] = p.left_out_styles;
    j["left_out"]["stages"] = stages(r.left_out);
    if (r.real_held_out) {
        j["real_held_out"] = metrics_json(r.real_held_out->network);
        j["real_held_out"]["stages"] = stages(*r.real_held_out);
        j["real_held_out"]["keyframes"] = r.real_held_out->keyframes;
        std::vector<std::string> names;
        for (const eval::UserFurniture& f : p.real_held_out) names.push_back(f.name);
        j["real_held_out"]["models"] = names;
    }
    if (r.clutter) {
        const eval::ClutterMetrics& c = *r.clutter;
        j["clutter"] = {{"keyframes", c.keyframes},
                        {"clutter_items", c.clutter_items},
                        {"network_detections", c.network},
                        {"network_per_keyframe", c.network_per_keyframe()},
                        {"map_objects", c.tracked},
                        {"map_objects_per_keyframe", c.tracked_per_keyframe()}};
        for (const double t : {0.4, 0.5, 0.6, 0.7}) {
            const auto above = std::count_if(c.network_scores.begin(), c.network_scores.end(),
                                             [t](double v) { return v >= t; });
            j["clutter"]["network_per_keyframe_at"][std::to_string(t).substr(0, 3)] =
                c.keyframes ? static_cast<double>(above) / static_cast<double>(c.keyframes) : 0.0;
        }
    }
    j["cad_library"] = o.no_cad ? "none" : o.default_cad ? "default" : "scene";
    j["cad_fit"] = std::string(eval::to_string(p.cad_fit));
    j["config"] = o.config.empty() ? io::Json(nullptr) : io::Json(o.config);
    j["shape_model"] = o.shape_model.empty() ? io::Json(nullptr) : io::Json(o.shape_model);
    j["latency_ms_median_1t"] = r.latency_ms_median_1t;
    j["latency_ms_p99_1t"] = r.latency_ms_p99_1t;
    j["latency_ms_median_2t"] = r.latency_ms_median_2t;
    j["latency_ms_p99_2t"] = r.latency_ms_p99_2t;
    j["keyframes"] = r.held_out.keyframes;
    j["left_out_keyframes"] = r.left_out.keyframes;
    j["scenes"] = o.scenes;
    j["max_keyframes"] = o.max_keyframes;
    j["seed"] = o.seed;
    j["beam_pattern"] = o.beam_pattern;
    j["sensor_height_m"] = o.sensor_height;
    j["level_height_m"] = detector.params().level_height_m;
    fs::create_directories(o.out_dir);
    io::write_json(fs::path(o.out_dir) / "summary.json", j);
    const auto& h = r.held_out;
    std::cout << std::fixed << std::setprecision(3) << "held-out mAP@0.25 / @0.5: network "
              << h.network.map_25 << " / " << h.network.map_50 << ", + verification "
              << h.verified.map_25 << " / " << h.verified.map_50 << ", + tracking "
              << h.tracked.map_25 << " / " << h.tracked.map_50
              << "; left-out styles (network): " << r.left_out.network.map_25 << " / "
              << r.left_out.network.map_50;
    if (r.real_held_out) {
        std::cout << "; real models held out: network " << r.real_held_out->network.map_25 << " / "
                  << r.real_held_out->network.map_50 << ", + tracking "
                  << r.real_held_out->tracked.map_25 << " / " << r.real_held_out->tracked.map_50;
    }
    if (r.clutter) {
        std::cout << "; clutter: " << r.clutter->network_per_keyframe()
                  << " false detections per keyframe, " << r.clutter->tracked_per_keyframe()
                  << " false map objects";
    }
    std::cout << "; latency " << r.latency_ms_median_2t << " ms (2 threads); wrote "
              << (fs::path(o.out_dir) / "summary.json").string() << "\n";
    return 0;
}

void declare_eval_detection(CommandSpec& c, EvalDetectionOptions& ev) {
    c.option("--model", ev.model, "Model file (default: models/detector.pt)");
    c.option("--scenes", ev.scenes, "Held-out scenes per set").range(1, 1000).show_default();
    c.option("--max-keyframes", ev.max_keyframes,
             "Keyframes per scene at most (as dataset's; fewer for a quick look)")
        .range(1, 1000)
        .show_default();
    c.option("--seed", ev.seed, "Seed of the held-out scenes (training uses smaller seeds)")
        .show_default();
    c.option("--out", ev.out_dir, "Output folder (summary.json)").show_default();
    c.flag("--no-cad", ev.no_cad,
           "No CAD models at all (with --shape-model: the learned shapes alone)");
    c.option("--shape-model", ev.shape_model,
             "Shape networks (models/shape.pt) for detections no CAD model fits")
        .existing_file();
    c.option("--shape-e-max", ev.shape_e_max,
             "Verification's residual bound for completed shapes [m]")
        .range(0.005, 0.5)
        .show_default();
    c.option("--config", ev.config,
             "YAML configuration: the online system's sections (perception, verification, "
             "tracking; default: built-in, see config/default.yaml)")
        .existing_file();
    c.option("--furniture", ev.furniture,
             "Real furniture models (furniture.yaml): the ones training left out "
             "(--furniture-holdout-every) furnish a third set of scenes")
        .existing_directory();
    c.option("--furniture-holdout-every", ev.furniture_holdout_every,
             "As given to dataset: every N-th model of each class is the held-out one")
        .range(1, 1000)
        .show_default();
    c.option("--clutter", ev.clutter,
             "Clutter items per room of the false-positive set (rooms of clutter alone; 0: "
             "no such set)")
        .range(0, 100)
        .show_default();
    c.option("--beam-pattern", ev.beam_pattern, "The simulated LiDAR's beams in every set")
        .choices(beam_pattern_names())
        .show_default();
    c.option("--sensor-height", ev.sensor_height, "The LiDAR's height above the floor [m]")
        .range(0.1, 3.0)
        .show_default();
    c.option("--cad-fit", ev.cad_fit,
             "How close each scene's CAD models are: exact (its own), scaled (0.9-1.1 per axis), "
             "other-dimensions (its style at other dimensions; real meshes scaled)")
        .choices(names_in(eval::cad_fits_by_name()))
        .show_default();
    c.flag("--default-cad", ev.default_cad,
           "Verify against one default-dimension model per style instead of the "
           "CAD models of each scene's own furniture");
}
const Registration<EvalDetectionOptions> kEvalDetection{
    "eval-detection", Group::kEvaluation,
    "AP/AR at 3D IoU 0.25 and 0.5, orientation accuracy and latency on "
    "held-out simulated scenes, and on styles left out of training",
    declare_eval_detection, run_eval_detection};

}  // namespace

}  // namespace makeway::apps
