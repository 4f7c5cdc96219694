// `makeway label`: the automatic annotation of recorded sessions.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "io/cad_folder.hpp"
#include "io/config_reader.hpp"
#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/labelling/labeller.hpp"
#include "ros/sweep_source.hpp"

namespace makeway::apps {

struct LabelOptions {
    std::vector<std::string>
        sessions;       ///< one folder per session (makeway simulate output or recorded sweeps)
    std::string cad;    ///< CAD folder; empty: PCA boxes only
    std::string model;  ///< the previous round's detector: classes of model-less clusters
    std::string config;
    std::string odometry_name = "odometry.txt";
    std::string poses_name;  ///< external poses (TUM T_world_sensor) in every session folder; the
                             ///< odometry does not run
    std::string out;
    int max_sweeps = 0;  ///< per session; 0: all
};

namespace fs = std::filesystem;
namespace {

// A session folder as `makeway simulate` writes it (clouds/ and odometry.txt) or as `makeway run`
// reads one (a folder of sweeps, odometry.txt beside or inside it); a .bag file is a ROS 1 bag.
rosio::SourceOptions session_source(const fs::path& dir, const LabelOptions& o,
                                    const Isometry3& T_base_sensor) {
    rosio::SourceOptions so;
    so.T_base_sensor = T_base_sensor;
    if (dir.extension() == ".bag") {
        so.bag = dir.string();
        return so;
    }
    if (!fs::is_directory(dir))
        throw io::FileError(
            dir, "not a session folder (sweeps, or clouds/ and odometry.txt) or a .bag file");
    so.clouds = fs::is_directory(dir / "clouds") ? (dir / "clouds").string() : dir.string();
    for (const fs::path& odo : {dir / o.odometry_name, fs::path(so.clouds) / o.odometry_name}) {
        if (fs::is_regular_file(odo))
            so.odometry = odo.string();
        else if (fs::exists(odo))
            throw io::FileError(
                odo, "is not a file: --odometry-name names the session's TUM odometry file");
    }
    if (!o.poses_name.empty()) {
        so.odometry.clear();
        for (const fs::path& poses : {dir / o.poses_name, fs::path(so.clouds) / o.poses_name}) {
            if (fs::is_regular_file(poses)) so.poses = poses.string();
        }
        if (so.poses.empty())
            throw io::FileError(dir / o.poses_name, "no such pose file (--poses-name)");
    }
    return so;
}

// The previous round's detector names model-less clusters: the cluster is put where a keyframe
// would see it (2 m ahead of a sensor at its mounting height) and the best detection over its box
// wins.
labelling::UnknownClassifier detector_classifier(const perception::Detector& detector,
                                                 const Isometry3& T_base_sensor) {
    return [&detector, T_base_sensor](
               int, const OrientedBox& box_world,
               const std::vector<Eigen::Vector3d>& points_world) -> std::optional<ObjectClass> {
        const Eigen::Vector3d at(box_world.centre_m.x() - 2.0, box_world.centre_m.y(),
                                 T_base_sensor.translation().z());
        const Isometry3 T_sensor_world = make_T_xyz_yaw(at, 0.0).inverse();
        PointCloud cloud;
        for (const Eigen::Vector3d& p : points_world)
            cloud.xyz.push_back((T_sensor_world * p).cast<float>());
        const OrientedBox box = box_world.transformed(T_sensor_world);
        std::optional<ObjectClass> cls;
        double best = 0.0;
        // The floor (world z = 0) is known here: at.z() below the virtual sensor.
        for (const Detection& d : detector.detect(cloud, Eigen::Vector4d(0, 0, 1, at.z()))) {
            if (iou_bev(d.box_sensor, box) > 0.1 && d.score > best) best = d.score, cls = d.cls;
        }
        return cls;
    };
}

void write_point_labels(const fs::path& path, const std::vector<std::uint32_t>& labels) {
    io::write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(labels.data()),
                                                 labels.size() * sizeof(std::uint32_t)));
}

}  // namespace

int run_label(const LabelOptions& o) {
    const io::Config cfg = io::load_config(o.config);
    labelling::LabelParams params = cfg.labelling;
    params.system = io::online_system_params(cfg);
    if (!o.poses_name.empty())
        params.system.lidar_odometry_enabled = false;  // the given poses are the pose
    std::optional<verification::CadLibrary> library;
    if (!o.cad.empty()) library = io::read_cad_folder(o.cad);
    std::optional<perception::Detector> detector;
    if (!o.model.empty()) detector.emplace(load_detector(o.model));
    // Every session is opened (and checked) before the long work starts.
    std::vector<std::unique_ptr<rosio::SweepSource>> sources;
    std::size_t total = 0;
    for (const std::string& dir : o.sessions) {
        sources.push_back(
            rosio::open_sweep_source(session_source(dir, o, params.system.T_base_sensor)));
        total += o.max_sweeps > 0 ? std::min<std::size_t>(sources.back()->size(),
                                                          static_cast<std::size_t>(o.max_sweeps))
                                  : sources.back()->size();
    }
    io::StagedOutput staged(o.out);  // the whole dataset or none of it
    labelling::Labeller labeller(params);
    std::cout << "label: " << o.sessions.size() << " sessions, " << total << " sweeps"
              << (library ? ", " + std::to_string(library->models().size()) + " CAD models"
                          : ", no CAD models (PCA boxes, unknown classes)")
              << (detector ? ", classes of model-less objects from " + o.model : "") << "\n";
    io::ProgressBar bar("label: sweeps", total);
    std::size_t done = 0;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        rosio::SweepSource& source = *sources[i];
        labeller.begin_session(source.first_pose().value_or(Pose2{}));
        std::size_t n = 0;
        while (std::optional<rosio::SourceSweep> s = source.next()) {
            if (o.max_sweeps > 0 && n >= static_cast<std::size_t>(o.max_sweeps)) break;
            if (!s->timed)
                throw io::FileError(s->file,
                                    "no per-point time field (time, t or timestamp): the sweep "
                                    "cannot be de-skewed");
            labeller.add_sweep(
                {std::move(s->points), s->stamp_s, s->duration_s, s->pose_start, s->pose_end});
            ++n;
            bar.update(++done);
        }
        if (n < static_cast<std::size_t>(params.system.keyframe.every)) {
            throw io::FileError(o.sessions[i], "fewer sweeps (" + std::to_string(n) +
                                                   ") than one keyframe needs (" +
                                                   std::to_string(params.system.keyframe.every) +
                                                   ")");
        }
    }
    bar.finish();
    std::string stage;
    std::optional<io::ProgressBar> step;
    const labelling::LabelResult r =
        labeller.finish(library ? &*library : nullptr,
                        detector ? detector_classifier(*detector, params.system.T_base_sensor)
                                 : labelling::UnknownClassifier{},
                        [&](const std::string& name, std::size_t d, std::size_t t) {
                            if (name != stage) {
                                if (step) step->finish();
                                stage = name;
                                step.emplace("label: " + name, t);
                            }
                            step->update(d);
                        });
    if (step) step->finish();

    const fs::path out = staged.staging();
    std::size_t index = 0, labelled = 0;
    io::Json sessions = io::Json::array();
    for (std::size_t s = 0; s < r.sessions.size(); ++s) {
        for (const labelling::LabelledSessionKeyframe& k : r.sessions[s]) {
            const std::string name = io::frame_name(index);
            io::write_labelled_keyframe(out, index, k.keyframe);
            write_point_labels(out / "point_labels" / (name + ".label"), k.point_labels);
            labelled += k.keyframe.objects.size();
            ++index;
        }
        const labelling::SessionReport& rep = r.reports[s];
        sessions.push_back(
            {{"folder", o.sessions[s]},
             {"sweeps", rep.sweeps},
             {"keyframes", rep.keyframes},
             {"alignment",
              {{"residual_m", rep.alignment.residual_m},
               {"inlier_fraction", rep.alignment.inlier_fraction},
               {"correction_m", rep.alignment.correction_m},
               {"correction_deg", rep.alignment.correction_deg},
               {"T_reference_session", io::pose_to_json(rep.alignment.T_reference_session)}}},
             {"clusters", rep.clusters},
             {"objects", rep.objects},
             {"cad_objects", rep.cad_objects},
             {"unknown_objects", rep.unknown_objects}});
    }
    io::Json objects = io::Json::array();
    for (const labelling::LabelledWorldObject& w : r.objects) {
        objects.push_back({{"id", w.id},
                           {"session", w.session},
                           {"class", w.cls ? std::string(to_string(*w.cls)) : "unknown"},
                           {"class_source", w.class_source},
                           {"model", w.model},
                           {"box_world", io::to_json(w.box_world)},
                           {"residual_m", w.residual_m},
                           {"seen_through", w.seen_through},
                           {"map_points", w.map_points},
                           {"movable_share", w.movable_share}});
    }
    io::Json counts = io::Json::object();
    for (int c = 0; c < labelling::kNumPointClasses; ++c)
        counts[std::string(labelling::to_string(static_cast<labelling::PointClass>(c)))] =
            r.point_class_counts[c];
    io::write_json(out / "objects.json", {{"objects", objects}});
    io::write_json(out / "meta.json", {{"auto_labelled", true},
                                       {"sessions", sessions},
                                       {"keyframes", index},
                                       {"objects", labelled},
                                       {"point_classes", counts},
                                       {"seconds",
                                        {{"front_end", r.seconds_front_end},
                                         {"align", r.seconds_align},
                                         {"ray_tracing", r.seconds_trace},
                                         {"objects", r.seconds_objects},
                                         {"labels", r.seconds_points}}}});
    staged.commit();
    std::cout << "wrote " << index << " keyframes with " << labelled << " labelled objects ("
              << r.objects.size() << " objects over " << r.sessions.size() << " sessions) to "
              << o.out << "\n";
    for (std::size_t s = 1; s < r.reports.size(); ++s) {
        std::printf(
            "session %zu aligned to session 1: residual %.1f mm, correction %.1f cm %.2f deg\n",
            s + 1, 1e3 * r.reports[s].alignment.residual_m,
            1e2 * r.reports[s].alignment.correction_m, r.reports[s].alignment.correction_deg);
    }
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_label(CommandSpec& c, LabelOptions& o) {
    c.option("--sessions", o.sessions,
             "Session folders (makeway simulate output: clouds/ and odometry.txt; or a "
             "folder of sweeps with odometry.txt) or .bag files, the first one the reference")
        .required()
        .expected(1, -1);
    c.option("--cad", o.cad,
             "CAD models of the room's furniture (chair_*.obj, table_*.obj, ...); without: "
             "PCA boxes, unknown classes");
    c.option("--model", o.model,
             "Detector weights of the previous round: the class of objects no CAD model fits");
    c.option("--config", o.config, "YAML configuration (the front end's sections)");
    c.option("--odometry-name", o.odometry_name,
             "Wheel odometry file name in each session folder (TUM)")
        .show_default();
    c.option("--poses-name", o.poses_name,
             "External poses in each session folder (TUM T_world_sensor at each sweep's "
             "start, e.g. makeway run's poses.txt): the odometry does not run");
    c.option("--max-sweeps", o.max_sweeps, "Sweeps per session at most (0: all)")
        .range(0, 10000000)
        .show_default();
    c.option("--out", o.out,
             "Output folder: clouds/, labels/ (as makeway dataset), point_labels/ (uint32: "
             "semantic low 16 bits, instance high 16), objects.json, meta.json")
        .required();
}
const Registration<LabelOptions> kLabel{
    "label", Group::kRecordedData,
    "Automatic annotation of recorded sessions of one place (the paper's six steps): "
    "sessions aligned, points classified by ray tracing (ground, permanent, "
    "movable, dynamic), movable points clustered, boxes by PCA and CAD alignment, "
    "per-point labels; writes a detector dataset",
    declare_label, run_label};

}  // namespace

}  // namespace makeway::apps
