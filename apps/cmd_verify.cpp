// makeway bench verify: the CAD verification benchmark (matched and mismatched models).
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "apps/commands.hpp"
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

}  // namespace makeway::apps
