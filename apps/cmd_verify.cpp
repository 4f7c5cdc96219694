// makeway bench verify: the CAD verification benchmark (matched and mismatched models).
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "apps/commands.hpp"
#include "io/json_io.hpp"
#include "io/tracking_io.hpp"
#include "io/progress.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/mesh_io.hpp"
#include "io/point_cloud_io.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/eval/verify_bench.hpp"
#include "makeway/perception/ground.hpp"

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
            {"false_acceptance_rate", a.false_acceptance_rate},
            {"ms_per_object_median", a.ms_per_object_median},
            {"ms_per_object_p99", a.ms_per_object_p99}};
}

// Every mesh in the folder, its class from its name: chair_*.obj, table_*.ply, ...
verification::CadLibrary read_cad_folder(const std::string& dir) {
    if (!std::filesystem::is_directory(dir)) throw io::FileError(dir, "not a folder of CAD meshes");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string ext = io::lower_extension(e.path());
        if (e.is_regular_file() && (ext == "obj" || ext == "ply" || ext == "stl" || ext == "dae")) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    verification::CadLibrary lib;
    for (const auto& f : files) {
        const std::string name = f.stem().string();
        const auto cls = parse_object_class(name.substr(0, name.find('_')));
        if (!cls) throw io::FileError(f.string(), "CAD file names must start with chair_ or table_");
        lib.add(name, *cls, io::read_mesh(f));
    }
    if (lib.models().empty()) throw io::FileError(dir, "no CAD meshes (.obj, .ply, .stl, .dae) in the folder");
    return lib;
}

}  // namespace

int run_verify(const VerifyOptions& options) {
    const PointCloud raw = io::read_point_cloud(options.cloud, {.non_finite = io::NonFinitePolicy::kDrop}).cloud;
    const std::vector<Detection> detections = io::read_detection_frame(options.detections).detections_sensor;
    const verification::CadLibrary library = read_cad_folder(options.cad_dir);
    // The floor under each object from the ground plane, when the cloud still holds the ground;
    // ground and ceiling points are then removed, as the pipeline does before detection.
    const perception::GroundPlaneResult ground = perception::fit_ground_plane(raw, {});
    const PointCloud cloud = perception::remove_ground_and_ceiling(raw, ground, {});
    io::Json results = io::Json::array();
    std::size_t accepted = 0;
    for (const Detection& det : detections) {
        std::optional<double> floor_z;
        if (ground.found) floor_z = ground.floor_z_at(det.box_sensor.centre_m.x(), det.box_sensor.centre_m.y());
        const verification::VerifiedDetection v = verification::verify_detection(cloud, det, library, {}, floor_z);
        accepted += v.accepted;
        results.push_back({{"class", std::string(to_string(det.cls))},
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
                           {"T_sensor_object", {{"t_m", {v.T_sensor_object.translation().x(), v.T_sensor_object.translation().y(),
                                                          v.T_sensor_object.translation().z()}},
                                                {"yaw_rad", yaw_of(v.T_sensor_object)}}}});
    }
    io::write_json(options.out, {{"cloud", options.cloud}, {"ground_found", ground.found}, {"verified", results}});
    std::cout << "verified " << detections.size() << " detections: " << accepted << " accepted; wrote " << options.out << "\n";
    return 0;
}

int run_bench_verify(const BenchVerifyOptions& options) {
    eval::VerifyBenchParams p;
    p.scenes = options.scenes;
    p.seed = options.seed;
    p.verify.min_yaw_margin = options.min_yaw_margin;
    io::ProgressBar bar("bench verify", static_cast<std::size_t>(p.scenes));
    const eval::VerifyBenchResult r = eval::run_verify_bench(p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    const io::Json j = {{"scenes", p.scenes},
                        {"seed", p.seed},
                        {"min_yaw_margin", p.verify.min_yaw_margin},
                        {"true_boxes", r.true_boxes},
                        {"false_boxes", r.false_boxes},
                        {"matched", to_json(r.matched)},
                        {"mismatched", to_json(r.mismatched)}};
    io::write_json(std::filesystem::path(options.out_dir) / "summary.json", j);
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace makeway::apps
