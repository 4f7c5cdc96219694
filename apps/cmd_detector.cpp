// makeway dataset, train-detector and detect (eval-detection: cmd_eval_detection.cpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/command.hpp"
#include "apps/detector_options.hpp"
#include "apps/model_path.hpp"
#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/top_down_png.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/eval/detection_dataset.hpp"
#include "makeway/pipeline/keyframe.hpp"

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

namespace fs = std::filesystem;

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

}  // namespace

}  // namespace makeway::apps
