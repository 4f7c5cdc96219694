// makeway bench verify: the CAD verification benchmark (matched and mismatched models).
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "apps/command.hpp"
#include "io/cad_folder.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/mesh_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/progress.hpp"
#include "io/tracking_io.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/eval/verify_bench.hpp"
#include "makeway/pipeline/keyframe.hpp"

namespace makeway::apps {

struct VerifyOptions {
    std::string cloud;
    std::string detections;
    std::string cad_dir;
    std::string out;
    std::string non_finite = "reject";  ///< as detect: NaN points are bad input unless dropped
};

struct BenchVerifyOptions {
    int scenes = 5;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_verify";
    double min_yaw_margin = 0.0;  ///< VerifyParams::min_yaw_margin
    double approx_e_max_m = 0.0;  ///< VerifyParams::approx_e_max_m
};

namespace {

io::Json to_json(const eval::OrientationStats& s) {
    return {{"objects", s.objects},
            {"yaw_within_10deg", s.yaw_within_10deg},
            {"yaw_within_30deg", s.yaw_within_30deg},
            {"median_yaw_error_deg", s.median_yaw_error_deg},
            {"median_centre_error_m", s.median_centre_error_m}};
}

io::Json to_json(const eval::VerifyBenchArm& a) {
    return {{"before", to_json(a.before)},
            {"after", to_json(a.after)},
            {"true_rejection_rate", a.true_rejection_rate},
            {"approximate_rate", a.approximate_rate},
            {"false_acceptance_rate", a.false_acceptance_rate},
            {"ms_per_object_median", a.ms_per_object_median},
            {"ms_per_object_p99", a.ms_per_object_p99}};
}

}  // namespace

int run_verify(const VerifyOptions& options) {
    const auto policy =
        options.non_finite == "drop" ? io::NonFinitePolicy::kDrop : io::NonFinitePolicy::kReject;
    const PointCloud raw = io::read_point_cloud(options.cloud, {.non_finite = policy}).cloud;
    const std::vector<Detection> detections =
        io::read_detection_frame(options.detections).detections_sensor;
    const verification::CadLibrary library = io::read_cad_folder(options.cad_dir);
    // The floor under each object from the ground plane, when the cloud still holds the ground;
    // ground and ceiling points are then removed, as the pipeline does before detection.
    const pipeline::PreparedKeyframe keyframe = pipeline::prepare_keyframe(raw, {});
    const PointCloud& cloud = keyframe.cloud_sensor;
    io::Json results = io::Json::array();
    std::size_t accepted = 0;
    for (const Detection& det : detections) {
        const std::optional<double> floor_z =
            keyframe.floor_z_at(det.box_sensor.centre_m.x(), det.box_sensor.centre_m.y());
        const verification::VerifiedDetection v =
            verification::verify_detection(cloud, det, library, {}, floor_z);
        accepted += v.accepted;
        results.push_back(
            {{"class", std::string(to_string(det.cls))},
             {"accepted", v.accepted},
             {"reason", v.reason},
             {"model", v.model},
             {"residual_m", v.residual_m},
             {"p_exist", v.p_exist},
             {"iterations", v.iterations},
             {"converged", v.converged},
             {"segment_points", v.segment_points},
             {"input_box", io::to_json(det.box_sensor)},
             {"box", io::to_json(v.box_sensor)},
             {"T_sensor_object",
              {{"t_m",
                {v.T_sensor_object.translation().x(), v.T_sensor_object.translation().y(),
                 v.T_sensor_object.translation().z()}},
               {"yaw_rad", yaw_of(v.T_sensor_object)}}}});
    }
    io::write_json(
        options.out,
        {{"cloud", options.cloud}, {"ground_found", keyframe.ground.found}, {"verified", results}});
    std::cout << "verified " << detections.size() << " detections: " << accepted
              << " accepted; wrote " << options.out << "\n";
    return 0;
}

int run_bench_verify(const BenchVerifyOptions& options) {
    eval::VerifyBenchParams p;
    p.scenes = options.scenes;
    p.seed = options.seed;
    p.verify.min_yaw_margin = options.min_yaw_margin;
    p.verify.approx_e_max_m = options.approx_e_max_m;
    if (const auto problems = p.verify.validate(); !problems.empty())
        throw io::FileError("--approx-e-max", problems.front());
    io::ProgressBar bar("bench verify", static_cast<std::size_t>(p.scenes));
    const eval::VerifyBenchResult r = eval::run_verify_bench(
        p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    const io::Json j = {{"scenes", p.scenes},
                        {"seed", p.seed},
                        {"min_yaw_margin", p.verify.min_yaw_margin},
                        {"approx_e_max_m", p.verify.approx_e_max_m},
                        {"true_boxes", r.true_boxes},
                        {"false_boxes", r.false_boxes},
                        {"matched", to_json(r.matched)},
                        {"mismatched", to_json(r.mismatched)},
                        {"scaled", to_json(r.scaled)}};
    io::write_json(std::filesystem::path(options.out_dir) / "summary.json", j);
    std::cout << io::dump_json(j, 2) << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_verify(CommandSpec& c, VerifyOptions& o) {
    c.option("--cloud", o.cloud,
             "Keyframe cloud in the sensor frame (.pcd, .ply, .bin); the floor under "
             "each object comes from its ground plane when it has one")
        .required();
    c.option("--detections", o.detections,
             "JSON: [{\"class\": \"chair\", \"box\": {\"centre_m\": [x, y, z], "
             "\"size_m\": [l, w, h], \"yaw_rad\": a}, \"score\": s}, ...]")
        .required();
    c.option("--cad", o.cad_dir,
             "Folder of CAD meshes named chair_*.obj / table_*.obj (also .ply, .stl, "
             ".dae), in their object frame: origin on the floor, x forward")
        .required();
    c.option("--non-finite", o.non_finite,
             "Points with NaN/inf coordinates: reject the file (bad input) or drop them")
        .choices({"reject", "drop"})
        .show_default();
    c.option("--out", o.out, "Result JSON (refined pose and box, residual [m], p_exist, model)")
        .required();
}
const Registration<VerifyOptions> kVerify{
    "verify", Group::kPointClouds,
    "Verify detections against CAD models: yaw + translation "
    "point-to-plane ICP from 4 yaw candidates, rejection by residual, "
    "existence probability (paper eq. 2)",
    declare_verify, run_verify};

void declare_bench_verify(CommandSpec& c, BenchVerifyOptions& ver_o) {
    c.option("--scenes", ver_o.scenes, "Scenes (alternating medium and dense)")
        .range(1, 1000)
        .show_default();
    c.option("--seed", ver_o.seed, "Seed of scenes and corruption").show_default();
    c.option("--out", ver_o.out_dir, "Output folder (summary.json)").show_default();
    c.option("--min-yaw-margin", ver_o.min_yaw_margin,
             "Reject fits whose best rival orientation is within this "
             "fraction of the winner's residual (0: off)")
        .range(0.0, 10.0)
        .show_default();
    c.option("--approx-e-max", ver_o.approx_e_max_m,
             "Accept fits up to this residual [m] as approximate (the network's "
             "score stays; 0: off, else above e_max 0.035)")
        .range(0.0, 0.999)
        .show_default();
}
const Registration<BenchVerifyOptions> kBenchVerify{
    "bench verify", Group::kEvaluation,
    "CAD verification on simulated keyframes: ground-truth boxes "
    "corrupted like detector output (noise, yaw flips) and false "
    "boxes on walls, with matching, non-matching and scaled CAD models",
    declare_bench_verify, run_bench_verify};

}  // namespace

}  // namespace makeway::apps
