// makeway run: the whole system on recorded data (a folder of sweeps or a ROS 1 bag), as a robot
// would run it: pose, keyframes, detection, verification, object map, object-aware costmap.
// Writes the object map per keyframe, the final map and costmap, pictures, timing; optionally a
// bag that RViz or Foxglove plays.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "apps/nav_report.hpp"
#include "io/cad_folder.hpp"
#include "io/canvas.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/map_server_io.hpp"
#include "io/nav_png.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/tracking_io.hpp"
#include "io/zones_io.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/shape/learned_prior.hpp"
#include "ros/bag_io.hpp"
#include "ros/sweep_source.hpp"

namespace makeway::apps {

struct RunOptions {
    std::string clouds, bag;  ///< one of them: a folder of sweeps, or a ROS 1 bag
    std::string odometry;     ///< folders: TUM wheel odometry of the base, line k at sweep k
    std::string poses;        ///< TUM T_world_sensor per sweep start: external poses, no odometry
    std::string cloud_topic = "/velodyne_points", odom_topic = "/odom";
    std::string map;                 ///< map_server YAML: the static layer (optional)
    std::string cad;                 ///< CAD folder for verification (optional: skipped without)
    std::string shape_model;         ///< shape networks for what no CAD model fits (optional)
    std::vector<double> extrinsics;  ///< x y z roll pitch yaw of the sensor on the base (default:
                                     ///< the config's robot)
    std::vector<double>
        start;  ///< x y yaw of the base at the first sweep (default: the first pose)
    std::string config, model;
    std::string zones;  ///< learned zones (makeway learn-zones) for the affordance layer
    std::string out = "out/run", out_bag;
    double rate_hz = 10.0;
    double costmap_size_m = 40.0,
           resolution_m = 0.05;  ///< without --map: a free square around the start
    int png_every = 1;           ///< a picture every n-th keyframe (0: none)
    int max_sweeps = 0;          ///< 0: all
    std::string non_finite = "reject";
    bool instantaneous = false;      ///< accept sweeps without per-point time (not de-skewed)
    bool skip_bad_messages = false;  ///< bags: skip and count damaged messages instead of stopping
};

namespace fs = std::filesystem;
namespace {

// Median and 99th percentile of each timed quantity, in summary.json.
struct Timings {
    std::map<std::string, std::vector<double>> ms;
    void add(const std::string& name, double v) { ms[name].push_back(v); }
    io::Json to_json() const {
        io::Json j = io::Json::object();
        for (const auto& [name, values] : ms) {
            const auto [median, p99] = median_p99(values);
            j[name] = {{"median", median}, {"p99", p99}, {"count", values.size()}};
        }
        return j;
    }
};

// Where the pictures look: what was driven and mapped, plus a margin, within the costmap.
void view_bounds(const std::vector<Pose2>& trajectory, const std::vector<ObjectEstimate>& objects,
                 const Costmap& map, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
    lo = Eigen::Vector2d::Constant(1e18), hi = -lo;
    for (const Pose2& p : trajectory)
        lo = lo.cwiseMin(Eigen::Vector2d(p.x_m, p.y_m)),
        hi = hi.cwiseMax(Eigen::Vector2d(p.x_m, p.y_m));
    for (const ObjectEstimate& o : objects)
        lo = lo.cwiseMin(o.box_world.centre_m.head<2>()),
        hi = hi.cwiseMax(o.box_world.centre_m.head<2>());
    lo -= Eigen::Vector2d::Constant(4.0), hi += Eigen::Vector2d::Constant(4.0);
    const Eigen::Vector2d map_hi =
        map.origin_m + map.resolution_m * Eigen::Vector2d(map.width, map.height);
    lo = lo.cwiseMax(map.origin_m),
    hi = hi.cwiseMin(map_hi).cwiseMax(lo + Eigen::Vector2d::Constant(1.0));
}

}  // namespace

int run_run(const RunOptions& o) {
    if (o.clouds.empty() && o.bag.empty()) {
        print_error("run: give --clouds DIR or --bag FILE");
        return kExitBadInput;
    }
    const io::Config cfg = io::load_config(o.config);
    std::optional<Isometry3> extrinsics;
    if (const std::string p = o.extrinsics.empty() ? "" : io::extrinsics_problem(o.extrinsics);
        !p.empty())
        throw io::FileError("--extrinsics", p);
    if (const std::string p = o.start.empty() ? "" : io::start_problem(o.start); !p.empty())
        throw io::FileError("--start", p);
    if (!o.extrinsics.empty()) {
        const std::vector<double>& e = o.extrinsics;
        extrinsics = make_T_xyz_rpy({e[0], e[1], e[2]}, e[3], e[4], e[5]);
    }
    pipeline::SystemParams params =
        io::online_system_params(cfg, extrinsics ? &*extrinsics : nullptr);
    params.navigator.affordance.learned = io::load_zones(o.zones);
    const bool external = !o.poses.empty();
    if (external)
        params.lidar_odometry_enabled = false;  // the given poses are the pose: no odometry runs

    rosio::SourceOptions so;
    so.clouds = o.clouds;
    so.bag = o.bag;
    so.odometry = o.odometry;
    so.poses = o.poses;
    so.topics = {o.cloud_topic, o.odom_topic};
    so.rate_hz = o.rate_hz;
    so.non_finite =
        o.non_finite == "drop" ? io::NonFinitePolicy::kDrop : io::NonFinitePolicy::kReject;
    so.T_base_sensor = params.T_base_sensor;
    so.skip_bad_messages = o.skip_bad_messages;
    const std::unique_ptr<rosio::SweepSource> source = rosio::open_sweep_source(so);
    const perception::Detector detector = load_online_detector(o.model);
    std::optional<verification::CadLibrary> library;
    if (!o.cad.empty()) library = io::read_cad_folder(o.cad);
    const Pose2 start = !o.start.empty() ? Pose2{o.start[0], o.start[1], o.start[2]}
                                         : source->first_pose().value_or(Pose2{});
    std::unique_ptr<shape::LearnedShapePrior> prior;
    if (!o.shape_model.empty()) {
        prior = std::make_unique<shape::LearnedShapePrior>(
            std::make_shared<const shape::ShapeModel>(load_shape_model(o.shape_model)));
    }
    pipeline::OnlineSystemSetup setup;
    setup.params = params;
    setup.start = start;
    if (!o.map.empty()) setup.map = io::read_map_server(o.map);
    setup.map_kind = o.map.empty() ? pipeline::MapKind::kNone : pipeline::MapKind::kFurnished;
    setup.free_area_m = o.costmap_size_m;
    setup.free_area_resolution_m = o.resolution_m;
    setup.detector = &detector;
    setup.library = library ? &*library : nullptr;
    setup.prior = prior.get();
    pipeline::OnlineSystem system(setup);  // mapping: no route is given, the command stays zero

    io::StagedOutput staged(o.out);  // everything or nothing
    const fs::path out = staged.staging();
    std::optional<rosio::BagWriter> bag;
    if (!o.out_bag.empty()) bag.emplace(o.out_bag);
    std::cout << "run: " << source->describe()
              << (library ? ", " + std::to_string(library->models().size()) + " CAD models"
                  : prior ? ", no CAD models"
                          : ", no CAD models (verification skipped)")
              << (prior ? ", shape networks" : "")
              << (external                        ? ", external poses (no odometry)"
                  : params.lidar_odometry_enabled ? ", LiDAR odometry"
                                                  : ", wheel odometry alone")
              << "\n";

    Timings timings;
    std::vector<Pose2> trajectory;
    std::vector<io::StampedPose> sensor_poses;
    std::vector<fs::path> pictures;
    std::vector<std::string> captions;
    std::size_t keyframes = 0, detections = 0, accepted = 0, points = 0, sweeps = 0;
    io::ProgressBar bar("run", source->size());
    while (std::optional<rosio::SourceSweep> s = source->next()) {
        if (o.max_sweeps > 0 && sweeps >= static_cast<std::size_t>(o.max_sweeps)) break;
        if (!s->timed && !o.instantaneous) {
            throw io::FileError(
                s->file,
                (s->item.empty() ? "" : s->item + ": ") +
                    "no per-point time field (time, t or timestamp): the sweep cannot be de-skewed "
                    "(--instantaneous takes each sweep as taken at once)");
        }
        points += s->points.size();
        const double stamp = s->stamp_s;
        const pipeline::OnlineStep step = system.process(
            {std::move(s->points), stamp, s->duration_s, s->pose_start, s->pose_end});
        ++sweeps;
        const pipeline::SweepResult& r = step.sweep;
        trajectory.push_back(r.pose);
        sensor_poses.push_back({stamp, r.T_world_sensor_start});
        timings.add("per_sweep_ms", step.per_sweep_ms());
        timings.add("pose_ms", r.timing.deskew_ms);
        if (r.odometry) timings.add("odometry_ms", r.timing.odometry_ms);
        timings.add("costmap_ms", step.control.nav.update_ms);
        const double end = stamp + s->duration_s;
        if (bag) {
            bag->write_odometry("/makeway/odometry", r.pose, 0.0, 0.0, end, "map", "base_link");
            bag->write_tf(lift_to_3d(r.pose), end, "map", "base_link");
        }
        if (r.keyframe) {
            const pipeline::KeyframeResult& k = *r.keyframe;
            timings.add("keyframe_ms", r.timing.keyframe_ms());
            timings.add("accumulate_ms", r.timing.accumulate_ms);
            timings.add("ground_ms", r.timing.ground_ms);
            timings.add("detect_ms", r.timing.detect_ms);
            if (library || prior) timings.add("verify_ms", r.timing.verify_ms);
            timings.add("track_ms", r.timing.track_ms);
            detections += k.detections.size();
            accepted += std::count_if(k.verified.begin(), k.verified.end(),
                                      [](const auto& v) { return v.accepted; });
            const std::string name = io::frame_name(keyframes);
            io::Json frame = io::objects_to_json(static_cast<int>(keyframes), k.stamp_s, r.objects);
            frame["T_world_sensor"] = io::pose_to_json(k.T_world_keyframe);
            frame["detections"] = k.detections.size();
            io::write_json(out / "objects" / (name + ".json"), frame);
            if (o.png_every > 0 && keyframes % static_cast<std::size_t>(o.png_every) == 0) {
                Eigen::Vector2d lo, hi;
                view_bounds(trajectory, r.objects, system.costmap(), lo, hi);
                char title[128];
                std::snprintf(title, sizeof(title), "keyframe %zu, t = %.1f s: %zu objects",
                              keyframes, k.stamp_s - sensor_poses.front().stamp_s,
                              r.objects.size());
                pictures.push_back(out / "keyframes" / (name + ".png"));
                io::write_map_png(pictures.back(), system.costmap(), r.objects,
                                  params.navigator.affordance, trajectory, lo, hi, title);
                captions.push_back("keyframe " + std::to_string(keyframes) + ": " +
                                   std::to_string(r.objects.size()) + " objects");
            }
            if (bag) {
                bag->write_costmap("/makeway/costmap", system.costmap(), end, "map");
                bag->write_markers("/makeway/objects", r.objects, params.navigator.affordance, end,
                                   "map");
                bag->write_text("/makeway/object_map", io::dump_json(frame), end);
            }
            ++keyframes;
        }
        bar.update(sweeps, std::to_string(keyframes) + " keyframes, " +
                               std::to_string(system.objects().size()) + " objects");
    }
    bar.finish();
    if (sweeps == 0) throw io::FileError(o.bag.empty() ? o.clouds : o.bag, "no sweeps");

    const std::vector<ObjectEstimate>& objects = system.objects();
    io::write_json(out / "objects.json", io::objects_to_json(static_cast<int>(keyframes),
                                                             sensor_poses.back().stamp_s, objects));
    io::write_map_server(out / "costmap.yaml", system.costmap());
    io::write_tum(out / "poses.txt", sensor_poses);
    Eigen::Vector2d lo, hi;
    view_bounds(trajectory, objects, system.costmap(), lo, hi);
    io::write_map_png(out / "map.png", system.costmap(), objects, params.navigator.affordance,
                      trajectory, lo, hi,
                      std::to_string(sweeps) + " sweeps, " + std::to_string(keyframes) +
                          " keyframes, " + std::to_string(objects.size()) + " objects");
    if (!pictures.empty()) io::write_contact_sheet(out / "keyframes.png", pictures, captions);
    std::size_t chairs = std::count_if(objects.begin(), objects.end(), [](const ObjectEstimate& x) {
        return x.cls == ObjectClass::kChair;
    });
    io::Json summary = {
        {"input", source->describe()},
        {"sweeps", sweeps},
        {"skipped_messages", source->skipped()},
        {"points", points},
        {"keyframes", keyframes},
        {"detections", detections},
        {"verification",
         (library ? "on: " + std::to_string(library->models().size()) + " CAD models from " + o.cad
          : prior ? std::string("on: no CAD models")
                  : std::string("skipped: no --cad")) +
             (prior ? ", shape networks from " + o.shape_model : std::string())},
        {"verified_accepted", accepted},
        {"pose", external                        ? "external (--poses)"
                 : params.lidar_odometry_enabled ? "LiDAR odometry"
                                                 : "wheel odometry"},
        {"objects", objects.size()},
        {"chairs", chairs},
        {"tables", objects.size() - chairs},
        {"static_map", o.map.empty()
                           ? "none (a free square of " + io::dump_json(o.costmap_size_m) + " m)"
                           : o.map},
        {"timing_ms", timings.to_json()},
        {"start_pose", {start.x_m, start.y_m, start.yaw_rad}}};
    io::write_json(out / "summary.json", summary);
    if (bag) bag->close();
    staged.commit();
    const auto [sweep_median, sweep_p99] = median_p99(timings.ms["per_sweep_ms"]);
    const auto [key_median, key_p99] = median_p99(
        timings.ms.count("keyframe_ms") ? timings.ms["keyframe_ms"] : std::vector<double>{0.0});
    char line[256];
    std::snprintf(line, sizeof(line),
                  "%zu sweeps, %zu keyframes, %zu objects (%zu chairs); per sweep %.1f ms median, "
                  "per keyframe %.1f ms median",
                  sweeps, keyframes, objects.size(), chairs, sweep_median, key_median);
    std::cout << line << "\nwrote " << o.out << (o.out_bag.empty() ? "" : " and " + o.out_bag)
              << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_run(CommandSpec& c, RunOptions& o) {
    auto& clouds =
        c.option("--clouds", o.clouds,
                 "Folder of sweeps (.pcd with a time/t field, .ply, .bin), in name order");
    auto& bag = c.option("--bag", o.bag,
                         "ROS 1 bag with sensor_msgs/PointCloud2 sweeps and nav_msgs/Odometry");
    clouds.excludes(bag);
    auto& wheels =
        c.option("--odometry", o.odometry,
                 "With --clouds: wheel odometry of the base (TUM, line k at sweep k's start)")
            .needs(clouds);
    auto& poses =
        c.option("--poses", o.poses,
                 "External poses (TUM T_world_sensor at each sweep's start, as `makeway odometry` "
                 "writes them): used as they are, the odometry does not run");
    poses.excludes(wheels);
    c.option("--cloud-topic", o.cloud_topic, "With --bag: the PointCloud2 topic").show_default();
    c.option("--odom-topic", o.odom_topic,
             "With --bag: the wheel odometry topic (optional in the bag)")
        .show_default();
    c.option("--map", o.map,
             "Static map (map_server YAML + PGM) for the costmap's static layer; objects "
             "stand in its free space");
    c.option(
        "--cad", o.cad,
        "Folder of CAD meshes (chair_*/table_*) for verification; without it the stage is skipped");
    c.option("--shape-model", o.shape_model,
             "Shape networks (models/shape.pt): detections no CAD model fits (all, without "
             "--cad) are verified against their completed shape")
        .existing_file();
    c.option("--extrinsics", o.extrinsics,
             "The sensor on the base: x y z roll pitch yaw [m, rad] (default: the "
             "config's robot section, 0.4 m above the base)")
        .expected(6);
    c.option("--start", o.start,
             "The base's pose at the first sweep in the map: x y yaw (default: the first "
             "odometry or external pose, else 0 0 0)")
        .expected(3);
    c.option("--config", o.config, "YAML configuration (config/default.yaml's sections)");
    c.option("--model", o.model, "Detector weights (default: models/detector.pt)");
    c.option("--zones", o.zones,
             "Learned affordance zones (makeway learn-zones) instead of the hand-drawn ones")
        .existing_file();
    c.option("--rate", o.rate_hz, "Sweeps per second when nothing gives stamps")
        .range(0.1, 100.0)
        .show_default();
    c.option("--size", o.costmap_size_m,
             "Without --map: side of the square costmap around the start [m]")
        .range(2.0, 1000.0)
        .show_default();
    c.option("--png-every", o.png_every, "A picture every n-th keyframe (0: none)")
        .range(0, 100000)
        .show_default();
    c.option("--max-sweeps", o.max_sweeps, "Stop after this many sweeps (0: all)")
        .range(0, 100000000)
        .show_default();
    c.option("--non-finite", o.non_finite,
             "Points with NaN/inf coordinates: reject (error) or drop")
        .choices({"reject", "drop"})
        .show_default();
    c.flag("--instantaneous", o.instantaneous,
           "Accept sweeps without a per-point time field, each taken at its "
           "stamp (not de-skewed); off: such a sweep is an error");
    c.flag("--skip-bad-messages", o.skip_bad_messages,
           "With --bag: skip messages that do not deserialise or hold "
           "nonsense, and sweeps stamped before the previous one (counted in "
           "summary.json); off: the first one is an error")
        .needs(bag);
    c.option("--out", o.out,
             "Output folder: objects/ per keyframe, objects.json, costmap.yaml/.pgm, poses.txt, "
             "keyframes/ and keyframes.png, map.png, summary.json")
        .show_default();
    c.option("--out-bag", o.out_bag,
             "Also a ROS 1 bag: /makeway/costmap (OccupancyGrid), /makeway/objects "
             "(MarkerArray), /makeway/object_map (String, JSON), /makeway/odometry, /tf");
}
const Registration<RunOptions> kRun{
    "run", Group::kRecordedData,
    "The whole system on recorded data (a folder of sweeps or a ROS 1 bag): pose, "
    "keyframes, detection, verification, object map, object-aware costmap",
    declare_run, run_run};

}  // namespace

}  // namespace makeway::apps
