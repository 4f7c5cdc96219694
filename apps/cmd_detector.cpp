// makeway dataset, train-detector, detect and eval-detection.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/commands.hpp"
#include "apps/model_path.hpp"
#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/furniture_folder.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "makeway/eval/detection_eval.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/shape/learned_prior.hpp"

namespace makeway::apps {
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

}  // namespace

int run_dataset(const DatasetOptions& o) {
    eval::DatasetParams p;
    p.scenes = o.scenes;
    p.seed = o.seed;
    p.exclude_styles = o.exclude_styles;
    p.keyframe_every = o.keyframe_every;
    p.max_keyframes_per_scene = o.max_keyframes;
    p.furniture_share = o.furniture_share;
    p.all_styles = o.all_styles;
    if (!o.furniture.empty()) {
        for (io::FurnitureMesh& m : io::read_furniture_folder(o.furniture, io::print_warning)) {
            p.furniture.push_back({m.name, m.cls, std::move(m.mesh_object)});
        }
    }
    io::ProgressBar bar("dataset", static_cast<std::size_t>(o.scenes));
    const auto kfs = eval::generate_detection_dataset(
        p, [&](int d, int) { bar.update(static_cast<std::size_t>(d)); });
    bar.finish();
    std::size_t objects = 0;
    io::StagedOutput staged(o.out);  // the whole dataset or none of it
    for (std::size_t k = 0; k < kfs.size(); ++k) {
        io::write_labelled_keyframe(staged.staging(), k, kfs[k]);
        objects += kfs[k].objects.size();
    }
    io::write_json(staged.staging() / "meta.json", {{"scenes", o.scenes},
                                                    {"seed", o.seed},
                                                    {"exclude_styles", o.exclude_styles},
                                                    {"keyframes", kfs.size()},
                                                    {"objects", objects},
                                                    {"all_styles", o.all_styles},
                                                    {"furniture", o.furniture},
                                                    {"furniture_meshes", p.furniture.size()}});
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
        samples.push_back(s);
    }
    perception::DetectorParams dp;
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
              << " parameters\n";
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
    const PointCloud cloud = pipeline::prepare_keyframe(raw, {}).cloud_sensor;
    io::Json dets = io::Json::array();
    const auto found = detector.detect(cloud);
    for (const Detection& d : found) {
        dets.push_back({{"class", std::string(to_string(d.cls))},
                        {"box", io::to_json(d.box_sensor)},
                        {"score", d.score},
                        {"class_probabilities", d.class_probabilities}});
    }
    io::write_json(o.out, {{"cloud", o.cloud}, {"detections", dets}});
    std::cout << found.size() << " detections; wrote " << o.out << "\n";
    return 0;
}

int run_eval_detection(const EvalDetectionOptions& o) {
    const perception::Detector detector = load_detector(o.model);
    eval::DetectionEvalParams p;
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
    io::ProgressBar bar("eval-detection", static_cast<std::size_t>(2 * o.scenes));
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
    j["cad_library"] = o.no_cad ? "none" : o.default_cad ? "default" : "scene";
    j["shape_model"] = o.shape_model.empty() ? io::Json(nullptr) : io::Json(o.shape_model);
    j["latency_ms_median_1t"] = r.latency_ms_median_1t;
    j["latency_ms_p99_1t"] = r.latency_ms_p99_1t;
    j["latency_ms_median_2t"] = r.latency_ms_median_2t;
    j["latency_ms_p99_2t"] = r.latency_ms_p99_2t;
    j["keyframes"] = r.held_out.keyframes;
    j["left_out_keyframes"] = r.left_out.keyframes;
    j["scenes"] = o.scenes;
    j["seed"] = o.seed;
    fs::create_directories(o.out_dir);
    io::write_json(fs::path(o.out_dir) / "summary.json", j);
    const auto& h = r.held_out;
    std::cout << std::fixed << std::setprecision(3) << "held-out mAP@0.25 / @0.5: network "
              << h.network.map_25 << " / " << h.network.map_50 << ", + verification "
              << h.verified.map_25 << " / " << h.verified.map_50 << ", + tracking "
              << h.tracked.map_25 << " / " << h.tracked.map_50
              << "; left-out styles (network): " << r.left_out.network.map_25 << " / "
              << r.left_out.network.map_50 << "; latency " << r.latency_ms_median_2t
              << " ms (2 threads); wrote " << (fs::path(o.out_dir) / "summary.json").string()
              << "\n";
    return 0;
}

}  // namespace makeway::apps
