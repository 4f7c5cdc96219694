// makeway dataset, train-detector, detect and eval-detection.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "io/config_reader.hpp"
#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/furniture_folder.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/top_down_png.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/eval/detection_dataset.hpp"
#include "makeway/eval/detection_eval.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/shape/learned_prior.hpp"

namespace makeway::apps {

struct DatasetOptions {
    /// The generator's parameters, filled by the options directly; the command line's defaults
    /// are 20 scenes with two styles held out of training.
    eval::DatasetParams params = [] {
        eval::DatasetParams p;
        p.scenes = 20;
        p.exclude_styles = {"armchair", "round_table"};
        return p;
    }();
    std::string
        furniture;  ///< a folder of the user's own furniture meshes (io/furniture_folder.hpp)
    int furniture_holdout_every = 0;  ///< eval::split_furniture: models kept for measuring
    std::string beam_pattern = "vlp32c";
    std::vector<double> variety_heights{0.3, 1.1};
    std::string out;
};

struct TrainDetectorOptions {
    std::vector<std::string> data;
    int epochs = 20;
    int batch = 8;
    double learning_rate = 2e-3;
    std::uint64_t seed = 0;
    int threads = 0;
    int width = 32;
    bool intensity = false;
    bool level = true;  ///< levelled by each keyframe's ground plane (perception/levelling.hpp)
    bool resume = false;
    std::string out;
};

struct DetectOptions {
    std::string model;  ///< empty: the default weights
    std::string cloud;
    std::string png;  ///< optional picture of the detections
    std::string non_finite =
        "reject";  ///< points with NaN/inf coordinates: reject the file or drop them
    std::string out;
};

struct EvalDetectionOptions {
    std::string model;
    int scenes = 6;
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

std::vector<std::string> beam_pattern_names() {
    std::vector<std::string> names;
    for (const auto& [name, pattern] : sim::beam_patterns_by_name()) names.push_back(name);
    return names;
}

/// The user's furniture folder read and split as eval::split_furniture does.
eval::FurnitureSplit read_furniture_split(const std::string& folder, int holdout_every) {
    std::vector<eval::UserFurniture> all;
    if (!folder.empty()) {
        for (io::FurnitureMesh& m : io::read_furniture_folder(folder, io::print_warning))
            all.push_back({m.name, m.cls, std::move(m.mesh_object)});
    }
    return eval::split_furniture(std::move(all), holdout_every);
}

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

}  // namespace

int run_dataset(const DatasetOptions& o) {
    eval::DatasetParams p = o.params;
    if (p.exclude_styles == std::vector<std::string>{"none"}) p.exclude_styles.clear();
    p.beam_pattern = *sim::parse_beam_pattern(o.beam_pattern);
    p.sensor_variety.height_min_m = std::min(o.variety_heights[0], o.variety_heights[1]);
    p.sensor_variety.height_max_m = std::max(o.variety_heights[0], o.variety_heights[1]);
    eval::FurnitureSplit split = read_furniture_split(o.furniture, o.furniture_holdout_every);
    p.furniture = std::move(split.train);
    std::vector<std::string> held_out;
    for (const eval::UserFurniture& f : split.held_out) held_out.push_back(f.name);
    io::ProgressBar bar("dataset", static_cast<std::size_t>(p.scenes));
    const auto kfs = eval::generate_detection_dataset(
        p, [&](int d, int) { bar.update(static_cast<std::size_t>(d)); });
    bar.finish();
    std::size_t objects = 0;
    io::StagedOutput staged(o.out);  // the whole dataset or none of it
    for (std::size_t k = 0; k < kfs.size(); ++k) {
        io::write_labelled_keyframe(staged.staging(), k, kfs[k]);
        objects += kfs[k].objects.size();
    }
    io::write_json(staged.staging() / "meta.json", {{"scenes", p.scenes},
                                                    {"seed", p.seed},
                                                    {"exclude_styles", p.exclude_styles},
                                                    {"keyframes", kfs.size()},
                                                    {"objects", objects},
                                                    {"all_styles", p.all_styles},
                                                    {"furniture", o.furniture},
                                                    {"furniture_meshes", p.furniture.size()},
                                                    {"furniture_held_out", held_out},
                                                    {"clutter_per_scene", p.clutter.count},
                                                    {"beam_pattern", o.beam_pattern},
                                                    {"sensor_height_m", p.sensor_height_m},
                                                    {"sensor_variety", p.sensor_variety.share},
                                                    {"variety_heights_m", o.variety_heights}});
    staged.commit();
    std::cout << "wrote " << kfs.size() << " keyframes with " << objects << " labelled objects to "
              << o.out << "\n";
    return 0;
}

int run_train_detector(const TrainDetectorOptions& o) {
    std::vector<LabelledKeyframe> data;
    for (const auto& dir : o.data) {
        auto part = io::read_detection_dataset(dir);
        std::move(part.begin(), part.end(), std::back_inserter(data));
    }
    std::vector<perception::TrainingSample> samples;
    for (const auto& kf : data) {
        perception::TrainingSample s;
        s.cloud_sensor = &kf.cloud_sensor;
        for (const auto& obj : kf.objects) s.boxes.emplace_back(obj.cls, obj.box_sensor);
        s.ground_plane_sensor = kf.ground_plane_sensor;
        samples.push_back(s);
    }
    perception::DetectorParams dp;
    // Levelled to the training's median sensor height, measured from the keyframes' ground
    // planes (datasets without planes: not levelled).
    std::vector<double> heights;
    for (const auto& kf : data) {
        if (kf.ground_plane_sensor) heights.push_back((*kf.ground_plane_sensor)(3));
    }
    if (o.level && !heights.empty())
        dp.level_height_m = std::round(percentile(heights, 0.5) * 100.0) / 100.0;
    dp.width = o.width;
    dp.grid.intensity = o.intensity;
    dp.seed = o.seed;
    perception::Detector detector(dp);
    perception::TrainParams tp;
    tp.epochs = o.epochs;
    tp.batch_size = o.batch;
    tp.learning_rate = o.learning_rate;
    tp.seed = o.seed;
    tp.threads = o.threads;
    tp.checkpoint = o.out + ".ckpt";
    if (!o.resume && fs::exists(tp.checkpoint)) fs::remove(tp.checkpoint);
    std::cout << "training on " << samples.size() << " keyframes, " << detector.parameter_count()
              << " parameters";
    if (dp.level_height_m > 0)
        std::cout << ", levelled to a sensor " << dp.level_height_m << " m above the floor ("
                  << heights.size() << " ground planes)";
    std::cout << "\n";
    io::ProgressBar bar("train", static_cast<std::size_t>(o.epochs) *
                                     ((samples.size() + static_cast<std::size_t>(o.batch) - 1) /
                                      static_cast<std::size_t>(o.batch)));
    double smoothed = 0.0;
    const auto reports = perception::train_detector(
        detector, samples, tp,
        [&](int step, int, double loss) {
            smoothed = smoothed == 0.0 ? loss : 0.98 * smoothed + 0.02 * loss;
            std::ostringstream s;
            s << "loss " << std::fixed << std::setprecision(3) << smoothed;
            bar.update(static_cast<std::size_t>(step), s.str());
        },
        [&](const perception::EpochReport& r) {
            std::cerr << "\nepoch " << r.epoch << ": loss " << r.mean_loss << " (heatmap "
                      << r.heatmap_loss << ", box " << r.box_loss << ")\n";
        });
    bar.finish();
    detector.save(o.out);
    fs::remove(tp.checkpoint);
    std::cout << "wrote " << o.out << " after " << reports.size() << " epochs";
    if (!reports.empty()) std::cout << ", final loss " << reports.back().mean_loss;
    std::cout << "\n";
    return 0;
}

int run_detect(const DetectOptions& o) {
    const perception::Detector detector = load_detector(o.model);
    const auto policy =
        o.non_finite == "drop" ? io::NonFinitePolicy::kDrop : io::NonFinitePolicy::kReject;
    const PointCloud raw = io::read_point_cloud(o.cloud, {.non_finite = policy}).cloud;
    const pipeline::PreparedKeyframe prepared = pipeline::prepare_keyframe(raw, {});
    const PointCloud& cloud = prepared.cloud_sensor;
    io::Json dets = io::Json::array();
    const auto found = detector.detect(cloud, prepared.ground.plane());
    for (const Detection& d : found) {
        dets.push_back({{"class", std::string(to_string(d.cls))},
                        {"box", io::to_json(d.box_sensor)},
                        {"score", d.score},
                        {"class_probabilities", d.class_probabilities}});
    }
    if (!o.png.empty()) {
        io::write_detections_png(o.png, raw, cloud, found, detector.reach_m(),
                                 fs::path(o.cloud).filename().string() + ": " +
                                     std::to_string(found.size()) + " detections");
    }
    io::write_json(o.out, {{"cloud", o.cloud}, {"detections", dets}});
    std::cout << found.size() << " detections; wrote " << o.out
              << (o.png.empty() ? "" : " and " + o.png) << "\n";
    return 0;
}

int run_eval_detection(const EvalDetectionOptions& o) {
    const perception::Detector detector = load_detector(o.model);
    eval::DetectionEvalParams p;
    p.system = io::load_config(o.config).system;
    p.scenes = o.scenes;
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
    p.cad_fit = o.cad_fit == "scaled"             ? eval::CadFit::kScaled
                : o.cad_fit == "other-dimensions" ? eval::CadFit::kOtherDimensions
                                                  : eval::CadFit::kExact;
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
    j["cad_fit"] = o.cad_fit;
    j["config"] = o.config.empty() ? io::Json(nullptr) : io::Json(o.config);
    j["shape_model"] = o.shape_model.empty() ? io::Json(nullptr) : io::Json(o.shape_model);
    j["latency_ms_median_1t"] = r.latency_ms_median_1t;
    j["latency_ms_p99_1t"] = r.latency_ms_p99_1t;
    j["latency_ms_median_2t"] = r.latency_ms_median_2t;
    j["latency_ms_p99_2t"] = r.latency_ms_p99_2t;
    j["keyframes"] = r.held_out.keyframes;
    j["left_out_keyframes"] = r.left_out.keyframes;
    j["scenes"] = o.scenes;
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

// The subcommands of this file, as --help lists them.
namespace {

void declare_dataset(CommandSpec& c, DatasetOptions& ds) {
    c.option("--scenes", ds.params.scenes, "Scenes (sparse, medium, dense in turn)")
        .range(1, 100000)
        .show_default();
    c.option("--seed", ds.params.seed, "Seed of the first scene").show_default();
    c.option("--exclude-styles", ds.params.exclude_styles,
             "Styles replaced by another of their class (held out of training); none: every "
             "style of the generated scenes")
        .delimiter(',')
        .show_default();
    c.option("--keyframe-every", ds.params.keyframe_every, "Sweeps between keyframes")
        .range(1, 1000)
        .show_default();
    c.option("--max-keyframes", ds.params.max_keyframes_per_scene, "Keyframes per scene at most")
        .range(1, 10000)
        .show_default();
    c.flag("--all-styles", ds.params.all_styles,
           "The wider world: every object a random style of its class among all twelve "
           "chair and nine table styles (stacking, sled and cantilever chairs, bar stools, "
           "benches, sofas, lounge chairs, pedestal, coffee, balcony, folding and side "
           "tables, desks), less --exclude-styles");
    c.option("--furniture", ds.furniture,
             "A folder of your own furniture meshes (OBJ/PLY/STL/DAE): furniture.yaml gives "
             "each file's class, units, up_axis and forward_axis, else chair_*/table_* names")
        .existing_directory();
    c.option("--furniture-share", ds.params.furniture_share,
             "Share of the objects of a class drawn with your meshes")
        .range(0.0, 1.0)
        .show_default();
    c.option("--furniture-holdout-every", ds.furniture_holdout_every,
             "Within each class, sorted by name, every N-th model of --furniture is left out "
             "(for eval-detection --furniture; 0: all are used)")
        .range(0, 1000)
        .show_default();
    c.option("--beam-pattern", ds.beam_pattern,
             "The LiDAR's beams (scenes not drawn by --sensor-variety)")
        .choices(beam_pattern_names())
        .show_default();
    c.option("--sensor-height", ds.params.sensor_height_m,
             "The LiDAR's height above the floor [m] (scenes not drawn by --sensor-variety)")
        .range(0.1, 3.0)
        .show_default();
    c.option("--sensor-variety", ds.params.sensor_variety.share,
             "Share of the scenes recorded with a random sensor: one of the four beam patterns "
             "at a height drawn in --variety-heights")
        .range(0.0, 1.0)
        .show_default();
    c.option("--variety-heights", ds.variety_heights, "MIN,MAX sensor height of those scenes [m]")
        .delimiter(',')
        .expected(2)
        .range(0.1, 3.0)
        .show_default();
    c.option("--clutter", ds.params.clutter.count,
             "Things of furniture size that are not furniture (crates, cabinets, bins, sofas, "
             "shelves, plants, standing people, lamps, boxes) per scene, unlabelled")
        .range(0, 100)
        .show_default();
    c.option("--out", ds.out, "Output folder (clouds/, labels/, meta.json)").required();
}
const Registration<DatasetOptions> kDataset{
    "dataset", Group::kLearning,
    "Simulated, labelled keyframes for the detector: drives through generated "
    "scenes, 5 sweeps per keyframe, ground and ceiling removed",
    declare_dataset, run_dataset};

void declare_train_detector(CommandSpec& c, TrainDetectorOptions& tr) {
    c.option("--data", tr.data, "Dataset folders (makeway dataset, or auto-labelled data)")
        .required();
    c.option("--epochs", tr.epochs, "Epochs").range(1, 10000).show_default();
    c.option("--batch", tr.batch, "Keyframes per batch").range(1, 512).show_default();
    c.option("--lr", tr.learning_rate, "Peak learning rate").range(1e-6, 1.0).show_default();
    c.option("--seed", tr.seed, "Seed of initialisation, shuffling and augmentation")
        .show_default();
    c.option("--threads", tr.threads, "Torch threads (0: default)").range(0, 256).show_default();
    c.option("--width", tr.width, "Channels of the first network stage")
        .range(4, 256)
        .show_default();
    c.flag("--intensity", tr.intensity, "Add a mean-intensity input channel (off: geometry only)");
    c.flag("--resume", tr.resume, "Continue from OUT.ckpt when it exists");
    c.flag("!--no-level", tr.level,
           "Do not level the keyframes by their ground planes (the model then takes clouds as "
           "the sensor gives them, mounted as in the training data)");
    c.option("--out", tr.out, "Model file (.pt)").required();
}
const Registration<TrainDetectorOptions> kTrainDetector{
    "train-detector", Group::kLearning,
    "Train the detector from C++ (libtorch, CPU): augmentation, AdamW, "
    "warm-up + cosine schedule, checkpoints every epoch",
    declare_train_detector, run_train_detector};

void declare_detect(CommandSpec& c, DetectOptions& dt) {
    c.option("--model", dt.model, "Model file (default: models/detector.pt)");
    c.option("--cloud", dt.cloud, "Keyframe cloud (.pcd, .ply, .bin)").required();
    c.option("--non-finite", dt.non_finite,
             "Points with NaN/inf coordinates: reject the file (bad input) or drop them")
        .choices({"reject", "drop"})
        .show_default();
    c.option("--out", dt.out, "Detections JSON (class, box, score, class_probabilities)")
        .required();
    c.option("--png", dt.png,
             "Also a picture from above: the points within the detector's reach (grey: ground "
             "and ceiling), each box with its class and score")
        .output();
}
const Registration<DetectOptions> kDetect{
    "detect", Group::kPointClouds,
    "Detect chairs and tables in a keyframe cloud (sensor frame); the ground "
    "plane and ceiling are removed first when found",
    declare_detect, run_detect};

void declare_eval_detection(CommandSpec& c, EvalDetectionOptions& ev) {
    c.option("--model", ev.model, "Model file (default: models/detector.pt)");
    c.option("--scenes", ev.scenes, "Held-out scenes per set").range(1, 1000).show_default();
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
        .choices({"exact", "scaled", "other-dimensions"})
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
