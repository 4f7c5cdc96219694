// makeway: the command-line front end. Parses options (CLI11) and calls one run_* per subcommand.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>

#include "apps/commands.hpp"
#include "io/error.hpp"
#include "io/interrupt.hpp"
#include "io/staged_output.hpp"
#include "makeway/sim/furniture.hpp"

namespace {

using namespace makeway::apps;

void add_info(CLI::App& app, InfoOptions& o) {
    auto* sub = app.add_subcommand("info",
                                   "Print one JSON object describing a point-cloud file: "
                                   "format, encoding, point count, fields, bounds [m], "
                                   "count of points with NaN/inf coordinates");
    sub->add_option("FILE", o.path, "Point cloud (.pcd, .ply, or KITTI .bin)")->required();
}

void add_config(CLI::App& app, ConfigOptions& o) {
    auto* sub =
        app.add_subcommand("config",
                           "Print the configuration: config/default.yaml as the stages' parameter "
                           "tables generate it, or FILE as makeway reads it (defaults filled in)");
    sub->add_option("FILE", o.file,
                    "A configuration file to read (checked: every problem listed, exit 2)")
        ->check(CLI::ExistingFile);
    sub->add_flag("--describe", o.describe, "One line per key: value, admitted values, unit, doc");
}

void add_convert(CLI::App& app, ConvertOptions& o) {
    auto* sub = app.add_subcommand("convert",
                                   "Convert a point cloud between PCD, PLY and KITTI .bin "
                                   "by file extension, keeping every field both hold");
    sub->add_option("IN", o.input, "Input cloud (.pcd, .ply, .bin)")->required();
    sub->add_option("OUT", o.output, "Output cloud (.pcd, .ply, .bin); written atomically")
        ->required();
    sub->add_option("--pcd-encoding", o.pcd_encoding, "PCD DATA encoding")
        ->check(CLI::IsMember({"ascii", "binary", "binary_compressed"}))
        ->capture_default_str();
    sub->add_option("--ply-encoding", o.ply_encoding, "PLY encoding (binary = little endian)")
        ->check(CLI::IsMember({"ascii", "binary"}))
        ->capture_default_str();
    sub->add_option("--non-finite", o.non_finite,
                    "Points with NaN/inf coordinates: reject the file, keep them, or drop them")
        ->check(CLI::IsMember({"reject", "keep", "drop"}))
        ->capture_default_str();
}

void add_demo(CLI::App& app, DemoOptions& o) {
    auto* sub = app.add_subcommand("demo",
                                   "Run the longest end-to-end path that exists on the "
                                   "built-in default scene and write its outputs");
    sub->add_option("--config", o.config,
                    "YAML configuration (default: built-in defaults; see "
                    "config/default.yaml)");
    sub->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
}

void add_cad(CLI::App& app, CadOptions& o) {
    auto* sub =
        app.add_subcommand("cad", "Write a procedural chair or table model (OBJ, PLY or STL)");
    std::vector<std::string> styles;
    std::string names;
    for (int i = 0; i < makeway::sim::kNumFurnitureStyles; ++i) {
        styles.emplace_back(makeway::sim::to_string(static_cast<makeway::sim::FurnitureStyle>(i)));
        names += (i ? ", " : "") + styles.back();
    }
    sub->add_option("--style", o.style, "One of " + names)
        ->required()
        ->check(CLI::IsMember(styles));
    sub->add_option("--seed", o.seed, "Seed of the dimensions (real furniture ranges)")
        ->capture_default_str();
    sub->add_option("--out", o.out,
                    "Mesh file (.obj, .ply, .stl); the object frame has its origin on the "
                    "floor at the footprint centre, x forward, z up")
        ->required();
}

void add_scene(CLI::App& app, SceneOptions& o) {
    auto* sub = app.add_subcommand("scene",
                                   "Generate an indoor scene (YAML) and its top-down picture (PNG "
                                   "beside it); every scene has a collision-free route start -> "
                                   "waypoint -> goal for the robot footprint");
    sub->add_option("--seed", o.seed, "Scene seed")->capture_default_str();
    sub->add_option("--density", o.density, "Number of objects and clutter")
        ->check(CLI::IsMember({"sparse", "medium", "dense"}))
        ->capture_default_str();
    sub->add_option("--layout", o.layout,
                    "random, or study_space: one room with 12 tables and 22 chairs")
        ->check(CLI::IsMember({"random", "study_space"}))
        ->capture_default_str();
    sub->add_option("--sessions", o.sessions,
                    "Recording sessions of the same building with furniture moved "
                    "between them; session k > 0 goes to NAME_sessionK.yaml")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    sub->add_flag("--no-people", o.no_people, "No walkers and no chair pushers");
    sub->add_option("--out", o.out, "Scene file (.yaml)")->capture_default_str();
}

void add_simulate(CLI::App& app, SimulateOptions& o) {
    auto* sub = app.add_subcommand("simulate",
                                   "Drive the simulated Jackal (VLP-32C LiDAR, 10 Hz) through a "
                                   "scene and record every sweep with ground truth");
    sub->add_option("--scene", o.scene,
                    "Scene file (.yaml) from `makeway scene` or written by hand")
        ->required();
    sub->add_option("--config", o.config,
                    "YAML configuration: its lidar, robot and odometry sections are used "
                    "(default: built-in VLP-32C on a Jackal; see config/default.yaml)");
    sub->add_option("--route", o.route,
                    "auto (shortest safe route start -> waypoint -> goal) or a text file "
                    "of 'x y' points [m], one per line")
        ->capture_default_str();
    sub->add_option("--frames", o.frames, "Sweeps to record (10 per second)")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    sub->add_option("--out", o.out_dir,
                    "Output folder: clouds/, objects/, poses_gt.txt, odometry.txt, "
                    "scene.png, summary.json")
        ->required();
    sub->add_option(
           "--format", o.format,
           "Cloud format: pcd (binary, with labels), bin (KITTI, labels "
           "in SemanticKITTI .label files) or bag (a ROS 1 bag, drive.bag, as a robot "
           "records it: /velodyne_points, /odom, /tf_static; the truth on /ground_truth/*)")
        ->check(CLI::IsMember({"pcd", "bin", "bag"}))
        ->capture_default_str();
    sub->add_option("--seed", o.seed, "Seed of sensor noise and odometry drift")
        ->capture_default_str();
    sub->add_option("--threads", o.threads, "Ray-casting threads")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    sub->add_flag("--allow-outside-paths", o.allow_outside_paths,
                  "Let the scene's `mesh:` paths leave the scene's folder (absolute, ../); off: a "
                  "scene reads only "
                  "files beside it");
}

void add_navigate(CLI::App& app, NavigateOptions& o) {
    auto* sub =
        app.add_subcommand("navigate",
                           "Drive the simulated Jackal start -> waypoint -> goal with the "
                           "layered costmap, A* and DWA at 10 Hz; writes run.json and route.png");
    sub->add_option("--scene", o.scene, "Scene file (.yaml)")->required();
    sub->add_option("--method", o.method,
                    "con (no semantics, inflation 3x robot radius), oppo (no semantics, "
                    "inflation = robot radius), gt-perc (affordance zones from ground truth), "
                    "ours (the online system on its own pose from wheel odometry: detector, "
                    "verification, object map)")
        ->check(CLI::IsMember({"con", "oppo", "gt-perc", "ours"}))
        ->capture_default_str();
    sub->add_option("--model", o.model, "Detector weights for ours (default: models/detector.pt)");
    sub->add_option("--config", o.config,
                    "YAML configuration: lidar, robot and affordance sections "
                    "(default: built-in; see config/default.yaml)");
    sub->add_option("--map", o.map,
                    "Static map in map_server format (YAML + PGM) instead of the scene's walls "
                    "and pillars; its resolution and origin become the costmap's");
    sub->add_option("--out", o.out_dir,
                    "Output folder: run.json, route.png, costmap.yaml/.pgm (master grid, "
                    "map_server format)")
        ->required();
    sub->add_option("--seed", o.seed, "Sensor-noise seed")->capture_default_str();
    sub->add_option("--time-limit", o.time_limit_s, "Seconds before the run counts as failed [s]")
        ->check(CLI::Range(1.0, 3600.0))
        ->capture_default_str();
    sub->add_flag("--allow-outside-paths", o.allow_outside_paths,
                  "Let the scene's `mesh:` paths leave the scene's folder (absolute, ../); off: a "
                  "scene reads only "
                  "files beside it");
}

void add_verify(CLI::App& app, VerifyOptions& o) {
    auto* sub =
        app.add_subcommand("verify",
                           "Verify detections against CAD models: yaw + translation "
                           "point-to-plane ICP from 4 yaw candidates, rejection by residual, "
                           "existence probability (paper eq. 2)");
    sub->add_option("--cloud", o.cloud,
                    "Keyframe cloud in the sensor frame (.pcd, .ply, .bin); the floor under "
                    "each object comes from its ground plane when it has one")
        ->required();
    sub->add_option("--detections", o.detections,
                    "JSON: [{\"class\": \"chair\", \"box\": {\"centre_m\": [x, y, z], "
                    "\"size_m\": [l, w, h], \"yaw_rad\": a}, \"score\": s}, ...]")
        ->required();
    sub->add_option("--cad", o.cad_dir,
                    "Folder of CAD meshes named chair_*.obj / table_*.obj (also .ply, .stl, "
                    ".dae), in their object frame: origin on the floor, x forward")
        ->required();
    sub->add_option("--non-finite", o.non_finite,
                    "Points with NaN/inf coordinates: reject the file (bad input) or drop them")
        ->check(CLI::IsMember({"reject", "drop"}))
        ->capture_default_str();
    sub->add_option("--out", o.out,
                    "Result JSON (refined pose and box, residual [m], p_exist, model)")
        ->required();
}

void add_track(CLI::App& app, TrackOptions& o, EvalTrackingOptions& e) {
    auto* sub = app.add_subcommand(
        "track",
        "Track objects across frames (GIoU + Hungarian, Kalman filters, class and "
        "existence fusion, occlusion) and write the object map per frame");
    sub->add_option("--detections", o.detections,
                    "makeway: folder of per-frame JSON ({\"stamp_s\", \"T_world_sensor\", "
                    "\"detections\"}); kitti: a tracking-format file or a folder of them")
        ->required();
    sub->add_option("--format", o.format, "makeway or kitti")
        ->check(CLI::IsMember({"makeway", "kitti"}))
        ->capture_default_str();
    sub->add_option("--poses", o.poses,
                    "TUM file of T_world_sensor, one per frame (makeway format)");
    sub->add_option("--config", o.config,
                    "YAML configuration: its tracking section (default: built-in; for kitti a "
                    "traffic preset per type: 80 m range, drop out of range, constant velocity, "
                    "README \"Tracking on KITTI\")");
    sub->add_option("--rate", o.rate_hz, "Frame rate of KITTI sequences [Hz]")
        ->check(CLI::Range(0.1, 1000.0))
        ->capture_default_str();
    sub->add_option("--range", o.range_m,
                    "Sensor range [m]: farther objects are neither matched nor judged")
        ->check(CLI::Range(0.1, 10000.0));
    sub->add_option("--classes", o.classes,
                    "Classes to track, comma separated (kitti: any type names, default every "
                    "type in the input but DontCare; makeway: chair, table)")
        ->delimiter(',');
    sub->add_option("--min-score", o.min_score,
                    "Detections scoring below this (after --score-transform) are not used");
    sub->add_option("--score-transform", o.score_transform,
                    "How scores become probabilities: none, sigmoid (raw "
                    "logits), or auto (sigmoid when any score is outside [0, 1])")
        ->check(CLI::IsMember({"auto", "none", "sigmoid"}))
        ->capture_default_str();
    sub->add_option("--out-of-range", o.out_of_range,
                    "Objects leaving the range: freeze (kept where last seen) or drop")
        ->check(CLI::IsMember({"freeze", "drop"}));
    sub->add_option("--fov-deg", o.fov_deg,
                    "kitti: write only objects within this horizontal field of view of the "
                    "sensor's x axis (KITTI's camera: 81.4)")
        ->check(CLI::Range(0.0, 360.0));
    sub->add_option("--output-score", o.output_score,
                    "kitti: the score written per box: detection (the matched "
                    "detection's, as given), existence (the track's fused "
                    "existence) or track-mean (the mean of its detections' so far)")
        ->check(CLI::IsMember({"detection", "existence", "track-mean"}))
        ->capture_default_str();
    auto* coast = sub->add_flag("--coasting", o.coasting,
                                "kitti: also write confirmed tracks of every type in frames "
                                "without a detection (their predicted boxes); default: each "
                                "type's preset (Pedestrian one frame, the others none)");
    sub->add_flag("--no-coasting", o.no_coasting,
                  "kitti: only boxes updated by a detection, for every type")
        ->excludes(coast);
    sub->add_option("--coasting-frames", o.coasting_frames,
                    "kitti, with --coasting: write a track's predicted box "
                    "at most this many frames after its last detection (0: "
                    "until the track is dropped)")
        ->check(CLI::Range(0, 1000))
        ->needs(coast);
    sub->add_flag("!--no-backfill", o.backfill,
                  "kitti: a track's output starts at the frame that confirms it (default: "
                  "at its first detection, the frames that led to it written too, as AB3DMOT)");
    sub->add_option("--out", o.out,
                    "Output folder: per-frame JSON objects, or one KITTI file per sequence; and "
                    "summary.json (frames per second, settings)")
        ->required();
    auto* ev = app.add_subcommand(
        "eval-tracking",
        "makeway: CLEAR MOT (MOTA, MOTP, ID switches, fragmentations) and "
        "HOTA (DetA, AssA) per class, 3D IoU; kitti: the KITTI protocol as "
        "AB3DMOT reports it (sAMOTA, AMOTA, AMOTP; DontCare, neighbouring classes)");
    ev->add_option(
          "--gt", e.gt,
          "Ground truth: folder of per-frame object JSON (as makeway simulate writes), or KITTI")
        ->required();
    ev->add_option("--tracks", e.tracks, "Tracks in the same format")->required();
    ev->add_option("--format", e.format, "makeway or kitti")
        ->check(CLI::IsMember({"makeway", "kitti"}))
        ->capture_default_str();
    ev->add_option("--classes", e.classes,
                   "kitti: classes to evaluate, comma separated (default: those in the tracks)")
        ->delimiter(',');
    ev->add_option("--iou", e.min_iou, "kitti: 3D IoU a match needs")
        ->check(CLI::Range(0.01, 1.0))
        ->capture_default_str();
    ev->add_option("--fov-deg", e.fov_deg,
                   "kitti: score only boxes within this horizontal field of view (0: all)")
        ->check(CLI::Range(0.0, 360.0));
    ev->add_flag("--devkit-rounding", e.devkit_rounding,
                 "kitti: AB3DMOT's evaluate.py's score handling, to the bit: it averages "
                 "each track's already averaged scores again at every threshold (a "
                 "track can drop out an ulp under its own score); off: one mean per track");
    ev->add_option("--out", e.out, "Also write the metrics as JSON");
}

void add_detector(CLI::App& app, DatasetOptions& ds, TrainDetectorOptions& tr, DetectOptions& dt,
                  EvalDetectionOptions& ev) {
    auto* d = app.add_subcommand(
        "dataset",
        "Simulated, labelled keyframes for the detector: drives through generated "
        "scenes, 5 sweeps per keyframe, ground and ceiling removed");
    d->add_option("--scenes", ds.scenes, "Scenes (sparse, medium, dense in turn)")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    d->add_option("--seed", ds.seed, "Seed of the first scene")->capture_default_str();
    d->add_option("--exclude-styles", ds.exclude_styles,
                  "Styles replaced by another of their class (held out of training)")
        ->delimiter(',')
        ->capture_default_str();
    d->add_option("--keyframe-every", ds.keyframe_every, "Sweeps between keyframes")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    d->add_option("--max-keyframes", ds.max_keyframes, "Keyframes per scene at most")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    d->add_flag("--all-styles", ds.all_styles,
                "The wider world: every object a random style of its class among all twelve "
                "chair and nine table styles (stacking, sled and cantilever chairs, bar stools, "
                "benches, sofas, lounge chairs, pedestal, coffee, balcony, folding and side "
                "tables, desks), less --exclude-styles");
    d->add_option("--furniture", ds.furniture,
                  "A folder of your own furniture meshes (OBJ/PLY/STL/DAE): furniture.yaml gives "
                  "each file's class, units, up_axis and forward_axis, else chair_*/table_* names")
        ->check(CLI::ExistingDirectory);
    d->add_option("--furniture-share", ds.furniture_share,
                  "Share of the objects of a class drawn with your meshes")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    d->add_option("--out", ds.out, "Output folder (clouds/, labels/, meta.json)")->required();
    auto* t =
        app.add_subcommand("train-detector",
                           "Train the detector from C++ (libtorch, CPU): augmentation, AdamW, "
                           "warm-up + cosine schedule, checkpoints every epoch");
    t->add_option("--data", tr.data, "Dataset folders (makeway dataset, or auto-labelled data)")
        ->required();
    t->add_option("--epochs", tr.epochs, "Epochs")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    t->add_option("--batch", tr.batch, "Keyframes per batch")
        ->check(CLI::Range(1, 512))
        ->capture_default_str();
    t->add_option("--lr", tr.learning_rate, "Peak learning rate")
        ->check(CLI::Range(1e-6, 1.0))
        ->capture_default_str();
    t->add_option("--seed", tr.seed, "Seed of initialisation, shuffling and augmentation")
        ->capture_default_str();
    t->add_option("--threads", tr.threads, "Torch threads (0: default)")
        ->check(CLI::Range(0, 256))
        ->capture_default_str();
    t->add_option("--width", tr.width, "Channels of the first network stage")
        ->check(CLI::Range(4, 256))
        ->capture_default_str();
    t->add_flag("--intensity", tr.intensity,
                "Add a mean-intensity input channel (off: geometry only)");
    t->add_flag("--resume", tr.resume, "Continue from OUT.ckpt when it exists");
    t->add_option("--out", tr.out, "Model file (.pt)")->required();
    auto* de = app.add_subcommand(
        "detect",
        "Detect chairs and tables in a keyframe cloud (sensor frame); the ground "
        "plane and ceiling are removed first when found");
    de->add_option("--model", dt.model, "Model file (default: models/detector.pt)");
    de->add_option("--cloud", dt.cloud, "Keyframe cloud (.pcd, .ply, .bin)")->required();
    de->add_option("--non-finite", dt.non_finite,
                   "Points with NaN/inf coordinates: reject the file (bad input) or drop them")
        ->check(CLI::IsMember({"reject", "drop"}))
        ->capture_default_str();
    de->add_option("--out", dt.out, "Detections JSON (class, box, score, class_probabilities)")
        ->required();
    auto* e =
        app.add_subcommand("eval-detection",
                           "AP/AR at 3D IoU 0.25 and 0.5, orientation accuracy and latency on "
                           "held-out simulated scenes, and on styles left out of training");
    e->add_option("--model", ev.model, "Model file (default: models/detector.pt)");
    e->add_option("--scenes", ev.scenes, "Held-out scenes per set")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    e->add_option("--seed", ev.seed, "Seed of the held-out scenes (training uses smaller seeds)")
        ->capture_default_str();
    e->add_option("--out", ev.out_dir, "Output folder (summary.json)")->capture_default_str();
    e->add_flag("--no-cad", ev.no_cad,
                "No CAD models at all (with --shape-model: the learned shapes alone)");
    e->add_option("--shape-model", ev.shape_model,
                  "Shape networks (models/shape.pt) for detections no CAD model fits")
        ->check(CLI::ExistingFile);
    e->add_option("--shape-e-max", ev.shape_e_max,
                  "Verification's residual bound for completed shapes [m]")
        ->check(CLI::Range(0.005, 0.5))
        ->capture_default_str();
    e->add_flag("--default-cad", ev.default_cad,
                "Verify against one default-dimension model per style instead of the "
                "CAD models of each scene's own furniture");
}

void add_odometry(CLI::App& app, OdometryOptions& o) {
    auto* sub = app.add_subcommand(
        "odometry",
        "LiDAR odometry fused with wheel odometry on recorded sweeps (per-point "
        "time de-skews them); writes the sensor pose at each sweep's start (TUM)");
    sub->add_option("--clouds", o.clouds,
                    "Folder of sweeps (.pcd with a time/t field, .ply, .bin), taken in name order")
        ->required();
    sub->add_option("--odometry", o.odometry,
                    "Wheel odometry (TUM, one base pose per sweep start, its stamps the sweeps'); "
                    "without it: constant velocity");
    sub->add_option("--config", o.config,
                    "YAML configuration: lidar_odometry and robot (sensor mount) sections");
    sub->add_option("--start", o.start, "The base's pose at the first sweep: x y yaw [m, m, rad]")
        ->expected(3)
        ->capture_default_str();
    sub->add_option("--rate", o.rate_hz, "Sweeps per second without odometry stamps")
        ->check(CLI::Range(0.1, 100.0))
        ->capture_default_str();
    sub->add_option("--out", o.out, "Poses (TUM: stamp x y z qx qy qz qw)")->required();
}

void add_run(CLI::App& app, RunOptions& o) {
    auto* sub = app.add_subcommand(
        "run",
        "The whole system on recorded data (a folder of sweeps or a ROS 1 bag): pose, "
        "keyframes, detection, verification, object map, object-aware costmap");
    auto* clouds =
        sub->add_option("--clouds", o.clouds,
                        "Folder of sweeps (.pcd with a time/t field, .ply, .bin), in name order");
    auto* bag = sub->add_option(
        "--bag", o.bag, "ROS 1 bag with sensor_msgs/PointCloud2 sweeps and nav_msgs/Odometry");
    clouds->excludes(bag);
    auto* wheels =
        sub->add_option(
               "--odometry", o.odometry,
               "With --clouds: wheel odometry of the base (TUM, line k at sweep k's start)")
            ->needs(clouds);
    auto* poses = sub->add_option(
        "--poses", o.poses,
        "External poses (TUM T_world_sensor at each sweep's start, as `makeway odometry` "
        "writes them): used as they are, the odometry does not run");
    poses->excludes(wheels);
    sub->add_option("--cloud-topic", o.cloud_topic, "With --bag: the PointCloud2 topic")
        ->capture_default_str();
    sub->add_option("--odom-topic", o.odom_topic,
                    "With --bag: the wheel odometry topic (optional in the bag)")
        ->capture_default_str();
    sub->add_option("--map", o.map,
                    "Static map (map_server YAML + PGM) for the costmap's static layer; objects "
                    "stand in its free space");
    sub->add_option(
        "--cad", o.cad,
        "Folder of CAD meshes (chair_*/table_*) for verification; without it the stage is skipped");
    sub->add_option("--shape-model", o.shape_model,
                    "Shape networks (models/shape.pt): detections no CAD model fits (all, without "
                    "--cad) are verified against their completed shape")
        ->check(CLI::ExistingFile);
    sub->add_option("--extrinsics", o.extrinsics,
                    "The sensor on the base: x y z roll pitch yaw [m, rad] (default: the "
                    "config's robot section, 0.4 m above the base)")
        ->expected(6);
    sub->add_option("--start", o.start,
                    "The base's pose at the first sweep in the map: x y yaw (default: the first "
                    "odometry or external pose, else 0 0 0)")
        ->expected(3);
    sub->add_option("--config", o.config, "YAML configuration (config/default.yaml's sections)");
    sub->add_option("--model", o.model, "Detector weights (default: models/detector.pt)");
    sub->add_option("--rate", o.rate_hz, "Sweeps per second when nothing gives stamps")
        ->check(CLI::Range(0.1, 100.0))
        ->capture_default_str();
    sub->add_option("--size", o.costmap_size_m,
                    "Without --map: side of the square costmap around the start [m]")
        ->check(CLI::Range(2.0, 1000.0))
        ->capture_default_str();
    sub->add_option("--png-every", o.png_every, "A picture every n-th keyframe (0: none)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    sub->add_option("--max-sweeps", o.max_sweeps, "Stop after this many sweeps (0: all)")
        ->check(CLI::Range(0, 100000000))
        ->capture_default_str();
    sub->add_option("--non-finite", o.non_finite,
                    "Points with NaN/inf coordinates: reject (error) or drop")
        ->check(CLI::IsMember({"reject", "drop"}))
        ->capture_default_str();
    sub->add_flag("--instantaneous", o.instantaneous,
                  "Accept sweeps without a per-point time field, each taken at its "
                  "stamp (not de-skewed); off: such a sweep is an error");
    sub->add_flag("--skip-bad-messages", o.skip_bad_messages,
                  "With --bag: skip messages that do not deserialise or hold "
                  "nonsense, and sweeps stamped before the previous one (counted in "
                  "summary.json); off: the first one is an error")
        ->needs(bag);
    sub->add_option(
           "--out", o.out,
           "Output folder: objects/ per keyframe, objects.json, costmap.yaml/.pgm, poses.txt, "
           "keyframes/ and keyframes.png, map.png, summary.json")
        ->capture_default_str();
    sub->add_option("--out-bag", o.out_bag,
                    "Also a ROS 1 bag: /makeway/costmap (OccupancyGrid), /makeway/objects "
                    "(MarkerArray), /makeway/object_map (String, JSON), /makeway/odometry, /tf");
}

void add_label(CLI::App& app, LabelOptions& o) {
    auto* sub = app.add_subcommand(
        "label",
        "Automatic annotation of recorded sessions of one place (the paper's six steps): "
        "sessions aligned, points classified by ray tracing (ground, permanent, "
        "movable, dynamic), movable points clustered, boxes by PCA and CAD alignment, "
        "per-point labels; writes a detector dataset");
    sub->add_option(
           "--sessions", o.sessions,
           "Session folders (makeway simulate output: clouds/ and odometry.txt; or a "
           "folder of sweeps with odometry.txt) or .bag files, the first one the reference")
        ->required()
        ->expected(1, -1);
    sub->add_option("--cad", o.cad,
                    "CAD models of the room's furniture (chair_*.obj, table_*.obj, ...); without: "
                    "PCA boxes, unknown classes");
    sub->add_option(
        "--model", o.model,
        "Detector weights of the previous round: the class of objects no CAD model fits");
    sub->add_option("--config", o.config, "YAML configuration (the front end's sections)");
    sub->add_option("--odometry-name", o.odometry_name,
                    "Wheel odometry file name in each session folder (TUM)")
        ->capture_default_str();
    sub->add_option("--poses-name", o.poses_name,
                    "External poses in each session folder (TUM T_world_sensor at each sweep's "
                    "start, e.g. makeway run's poses.txt): the odometry does not run");
    sub->add_option("--max-sweeps", o.max_sweeps, "Sweeps per session at most (0: all)")
        ->check(CLI::Range(0, 10000000))
        ->capture_default_str();
    sub->add_option("--out", o.out,
                    "Output folder: clouds/, labels/ (as makeway dataset), point_labels/ (uint32: "
                    "semantic low 16 bits, instance high 16), objects.json, meta.json")
        ->required();
}

void add_shape(CLI::App& app, TrainShapeOptions& tr, BenchShapeOptions& be, CompleteOptions& co) {
    auto* t = app.add_subcommand(
        "train-shape",
        "Train the shape networks (F_n correspondences + 7-DoF solve, F_0 DeepSDF prior, "
        "F_1 TSDF-to-occupancy completion) on the simulator's furniture, from a fixed seed");
    t->add_option("--scenes", tr.scenes, "Rooms rendered for training")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    t->add_option("--seed", tr.seed, "Seed of rooms, initialisation and sampling")
        ->capture_default_str();
    t->add_option("--exclude-styles", tr.exclude_styles,
                  "Styles left out of training (bench shape scores them apart)")
        ->delimiter(',')
        ->capture_default_str();
    t->add_option("--steps-scale", tr.steps_scale, "Every stage's step count times this")
        ->check(CLI::Range(0.001, 100.0))
        ->capture_default_str();
    t->add_option("--threads", tr.threads, "Threads (torch and the targets)")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    t->add_option("--out", tr.out, "Model file (.pt); a report beside it (.pt.json)")
        ->capture_default_str();
    auto* c = app.add_subcommand(
        "complete",
        "Pose one object with F_n and complete its shape with F_1 (F_0's code as prior); "
        "writes the mesh in the cloud's frame");
    c->add_option("--model", co.model, "Shape model (default: models/shape.pt)");
    c->add_option("--cloud", co.cloud,
                  "Cloud holding the object (.pcd, .ply, .bin), ground not removed is fine")
        ->required();
    c->add_option(
         "--box", co.box,
         "The object's box in the cloud's frame: cx,cy,cz,length,width,height,yaw (a detection)")
        ->required();
    c->add_option("--class", co.cls, "chair or table")->required();
    c->add_option("--sensor", co.sensor, "Where the cloud was seen from, in its frame: x,y,z")
        ->capture_default_str();
    c->add_option("--out", co.out, "Mesh file (.obj, .ply, .stl)")->required();
    (void)be;
}

void add_bench(CLI::App& app, BenchSimOptions& o, BenchNavOptions& nav_o,
               BenchMergeOptions& merge_o, BenchVerifyOptions& ver_o, BenchTrackOptions& trk_o,
               BenchOdometryOptions& odo_o, BenchLabelOptions& lab_o, BenchSessionsOptions& ses_o,
               BenchShapeOptions& shape_o) {
    auto* bench = app.add_subcommand("bench", "Benchmarks that print JSON");
    bench->require_subcommand(1);
    auto* ses = bench->add_subcommand(
        "sessions",
        "Session after session: a detector trained without some styles is fine-tuned "
        "on auto-labels of multi-session drives of rooms furnished with them; the "
        "left-out and trained styles' mAP after each round");
    ses->add_option("--model", ses_o.model,
                    "Detector to start from (default: models/detector.pt, trained without "
                    "armchairs and round tables)");
    ses->add_option("--rounds", ses_o.rounds, "Rounds of label + fine-tune")
        ->check(CLI::Range(1, 20))
        ->capture_default_str();
    ses->add_option("--scenes-per-round", ses_o.scenes_per_round,
                    "Rooms driven and labelled per round")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    ses->add_option("--sessions", ses_o.sessions, "Sessions per room")
        ->check(CLI::Range(2, 20))
        ->capture_default_str();
    ses->add_option("--max-sweeps", ses_o.max_sweeps, "Sweeps per session at most")
        ->check(CLI::Range(10, 100000))
        ->capture_default_str();
    ses->add_option("--epochs", ses_o.epochs, "Fine-tuning epochs per round")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    ses->add_option("--replay-scenes", ses_o.replay_scenes,
                    "Simulated scenes of the trained styles replayed in fine-tuning")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    ses->add_option("--eval-scenes", ses_o.eval_scenes, "Held-out scenes per scored set")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    ses->add_option("--left-out-styles", ses_o.left_out_styles, "Styles the detector never saw")
        ->delimiter(',')
        ->capture_default_str();
    ses->add_option("--threads", ses_o.threads, "Torch threads")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    ses->add_option("--seed", ses_o.seed, "Seed of rooms, replay data and fine-tuning")
        ->capture_default_str();
    ses->add_option("--out", ses_o.out_dir,
                    "Output folder (summary.json, table.md, model.pt: the fine-tuned detector)")
        ->capture_default_str();
    auto* lab = bench->add_subcommand(
        "label",
        "The automatic annotation against the simulator's truth: multi-session "
        "drives (furniture moved between sessions), point-class IoU, panoptic "
        "quality, box AP@0.25/0.5 and yaw within 10 deg of the auto-labels");
    lab->add_option("--scenes", lab_o.scenes, "Scenes (alternating medium and dense)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    lab->add_option("--sessions", lab_o.sessions, "Sessions per scene")
        ->check(CLI::Range(2, 20))
        ->capture_default_str();
    lab->add_option("--seed", lab_o.seed, "Seed of scenes, sessions, sensor noise and wheel drift")
        ->capture_default_str();
    lab->add_option("--max-sweeps", lab_o.max_sweeps, "Sweeps per session at most (10 per second)")
        ->check(CLI::Range(10, 100000))
        ->capture_default_str();
    lab->add_flag("--no-cad", lab_o.no_cad,
                  "Without CAD models: every object keeps its PCA box, unknown class");
    lab->add_option("--out", lab_o.out_dir, "Output folder (summary.json)")->capture_default_str();
    auto* odo = bench->add_subcommand(
        "odometry",
        "LiDAR odometry on simulated drives (medium and dense scenes with people "
        "and pulled chairs, corridors): ATE, RPE over 1 m and 5 m, sweeps per second; "
        "writes summary.json and table.md");
    odo->add_option("--config", odo_o.config,
                    "YAML configuration: lidar, robot, wheel_noise and lidar_odometry sections");
    odo->add_option("--scenes", odo_o.scenes, "Drives (every fifth a corridor)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    odo->add_option("--seed", odo_o.seed, "Seed of scenes, sensor noise and wheel drift")
        ->capture_default_str();
    odo->add_option("--max-sweeps", odo_o.max_sweeps, "Sweeps per drive at most")
        ->check(CLI::Range(10, 100000))
        ->capture_default_str();
    odo->add_option("--out", odo_o.out_dir, "Output folder (summary.json, table.md)")
        ->capture_default_str();
    auto* trk = bench->add_subcommand(
        "track",
        "Tracking on simulated drives: visible objects' ground truth corrupted "
        "(20 % missed, 10 % false positives, noise, yaw flips); MOTA, HOTA, "
        "map yaw accuracy, frames per second");
    trk->add_option("--scenes", trk_o.scenes, "Scenes (alternating medium and dense)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    trk->add_option("--seed", trk_o.seed, "Seed of scenes and corruption")->capture_default_str();
    trk->add_option("--config", trk_o.config,
                    "YAML configuration: its tracking section replaces the defaults");
    trk->add_option("--out", trk_o.out_dir, "Output folder (summary.json)")->capture_default_str();
    trk->add_flag("--scan-occlusion", trk_o.scan_occlusion,
                  "Also treat LiDAR returns in front of an object as occlusion "
                  "(walls, people), beyond the paper's object boxes");
    auto* ver =
        bench->add_subcommand("verify",
                              "CAD verification on simulated keyframes: ground-truth boxes "
                              "corrupted like detector output (noise, yaw flips) and false "
                              "boxes on walls, with matching, non-matching and scaled CAD models");
    ver->add_option("--scenes", ver_o.scenes, "Scenes (alternating medium and dense)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    ver->add_option("--seed", ver_o.seed, "Seed of scenes and corruption")->capture_default_str();
    ver->add_option("--out", ver_o.out_dir, "Output folder (summary.json)")->capture_default_str();
    ver->add_option("--min-yaw-margin", ver_o.min_yaw_margin,
                    "Reject fits whose best rival orientation is within this "
                    "fraction of the winner's residual (0: off)")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    ver->add_option("--approx-e-max", ver_o.approx_e_max_m,
                    "Accept fits up to this residual [m] as approximate (the network's "
                    "score stays; 0: off, else above e_max 0.035)")
        ->check(CLI::Range(0.0, 0.999))
        ->capture_default_str();
    auto* nav =
        bench->add_subcommand("nav",
                              "The navigation benchmark (the paper's Table II): every method on "
                              "generated scenes of varied density; writes results.json, table.md "
                              "and one PNG per scene");
    nav->add_option("--config", nav_o.config,
                    "YAML configuration: lidar, robot and affordance sections");
    nav->add_option("--scenes", nav_o.scenes,
                    "Number of scenes (density cycles sparse, medium, dense)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    nav->add_option("--seed", nav_o.seed, "Seed of the first scene")->capture_default_str();
    nav->add_option("--out", nav_o.out_dir, "Output folder")->capture_default_str();
    nav->add_option("--threads", nav_o.threads, "Runs in parallel")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    nav->add_option("--model", nav_o.model,
                    "Detector weights for the full system ours (default: models/detector.pt "
                    "when present; without weights ours is left out)");
    nav->add_option("--shape-model", nav_o.shape_model,
                    "Shape networks: `ours` verifies against its learned shapes instead of "
                    "the scenes' CAD models")
        ->check(CLI::ExistingFile);
    nav->add_option("--methods", nav_o.methods,
                    "Only these methods (con, oppo, gt-perc, ours), comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember({"con", "oppo", "gt-perc", "ours"}));
    nav->add_option("--time-limit", nav_o.time_limit_s,
                    "Seconds per run before it counts as failed [s]")
        ->check(CLI::Range(1.0, 3600.0))
        ->capture_default_str();
    nav->add_option("--layout", nav_o.layout,
                    "random (densities cycle sparse, medium, dense) or study_space (the paper's "
                    "room of 12 tables and 22 chairs, one per seed)")
        ->check(CLI::IsMember({"random", "study_space"}))
        ->capture_default_str();
    nav->add_option("--shard", nav_o.shard,
                    "K/N: run only scenes K, K+N, K+2N, ... (0 <= K < N) and write partial.json; "
                    "`makeway bench merge` joins the N partials into the unsharded results")
        ->check(CLI::Validator(
            [](std::string& v) {
                return parse_shard(v) ? std::string() : "expected K/N with 0 <= K < N";
            },
            "K/N"));
    auto* merge = bench->add_subcommand(
        "merge",
        "Join `bench nav --shard K/N` partial results (one folder per shard) into "
        "exactly the results one unsharded run writes");
    merge
        ->add_option("dirs", merge_o.dirs,
                     "Folders holding partial.json, one per shard, in any order")
        ->required()
        ->check(CLI::ExistingDirectory);
    merge->add_option("--out", merge_o.out_dir, "Output folder")->capture_default_str();
    auto* shp = bench->add_subcommand(
        "shape",
        "The shape networks on held-out rooms and on the styles left out of training: "
        "F_n pose accuracy, completion (Chamfer-L1, IoU) of the partial cloud, F_0 and F_1, "
        "timing; writes summary.json, table.md, gallery.png");
    shp->add_option("--model", shape_o.model, "Shape model (default: models/shape.pt)");
    shp->add_option("--scenes", shape_o.scenes, "Rooms per set")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    shp->add_option("--seed", shape_o.seed, "Seed of the rooms (training uses small seeds)")
        ->capture_default_str();
    shp->add_option("--left-out", shape_o.left_out,
                    "Styles left out of training: a second set furnished only with them")
        ->delimiter(',')
        ->capture_default_str();
    shp->add_option("--threads", shape_o.threads, "Torch threads (timing is per object on these)")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    shp->add_option("--inlier-distance", shape_o.inlier_distance,
                    "The 7-DoF solve's inlier residual [m]")
        ->check(CLI::Range(0.001, 1.0))
        ->capture_default_str();
    shp->add_option("--hypotheses", shape_o.hypotheses,
                    "The 7-DoF solve's minimal samples (0: the weighted least squares alone)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    shp->add_flag("--pose-only", shape_o.pose_only, "Score F_n's pose only (no completion)");
    shp->add_option("--out", shape_o.out_dir, "Output folder")->capture_default_str();
    auto* sim =
        bench->add_subcommand("sim",
                              "LiDAR simulation speed: full VLP-32C sweeps (57,600 rays) in a "
                              "20 x 20 m room with 40 objects, on 1 and 2 threads");
    sim->add_option("--seed", o.seed, "Scene seed")->capture_default_str();
    sim->add_option("--sweeps", o.sweeps, "Sweeps timed per configuration (median reported)")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    sim->add_option("--out", o.out, "Also write the JSON to this file");
}

// Every number at the boundary: a FLOAT option must be finite (CLI11 reads "nan" and "inf" as
// numbers, and a NaN passes a Range check), an unsigned one must be written as a whole number that
// fits (CLI11 saturates "-1" and "1e23" to 2^64-1).
void check_numbers(CLI::App& app) {
    const CLI::Validator finite(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            return end != text.c_str() && !std::isfinite(v) ? "must be a finite number" : "";
        },
        "", "finite");
    const CLI::Validator whole(
        [](std::string& text) -> std::string {
            if (text.empty() || !std::all_of(text.begin(), text.end(),
                                             [](unsigned char c) { return std::isdigit(c); })) {
                return "must be a non-negative whole number";
            }
            errno = 0;
            (void)std::strtoull(text.c_str(), nullptr, 10);
            return errno == ERANGE ? "is too large (at most 18446744073709551615)" : "";
        },
        "", "whole");
    for (CLI::Option* o : app.get_options()) {
        const std::string type = o->get_type_name();
        if (type.rfind("FLOAT", 0) == 0) o->check(finite);
        if (type.rfind("UINT", 0) == 0) o->check(whole);
    }
    for (CLI::App* sub : app.get_subcommands({})) check_numbers(*sub);
}

// Every path option of the chosen subcommand: outputs (--out, --out-bag, OUT) and the inputs
// (any other value naming something that exists), for refuse_outputs_over_inputs.
void collect_paths(const CLI::App& app, std::vector<std::pair<std::string, std::string>>& outputs,
                   std::vector<std::pair<std::string, std::string>>& inputs) {
    for (const CLI::Option* o : app.get_options()) {
        if (o->count() == 0) continue;
        const std::string name = o->get_name();
        const bool output = name == "--out" || name == "--out-bag" || name == "OUT";
        for (const std::string& value : o->results()) {
            std::error_code ec;
            if (output)
                outputs.emplace_back(name, value);
            else if (std::filesystem::exists(value, ec))
                inputs.emplace_back(name, value);
        }
    }
    for (const CLI::App* sub : app.get_subcommands()) collect_paths(*sub, outputs, inputs);
}

}  // namespace

int main(int argc, char** argv) {
    makeway::io::install_interrupt_handlers();
    CLI::App app{
        "makeway: object-aware affordance costmaps for proactive indoor navigation "
        "with a 3D LiDAR"};
    app.set_version_flag("--version", "makeway 0.1.0");
    app.require_subcommand(1);
    InfoOptions info;
    ConfigOptions config;
    ConvertOptions convert;
    DemoOptions demo;
    CadOptions cad;
    SceneOptions scene;
    SimulateOptions simulate;
    BenchSimOptions bench_sim;
    NavigateOptions navigate;
    BenchNavOptions bench_nav;
    BenchMergeOptions bench_merge;
    BenchVerifyOptions bench_verify;
    VerifyOptions verify;
    DatasetOptions dataset;
    TrainDetectorOptions train_detector;
    DetectOptions detect;
    EvalDetectionOptions eval_detection;
    TrackOptions track;
    EvalTrackingOptions eval_tracking;
    BenchTrackOptions bench_track;
    OdometryOptions odometry;
    BenchOdometryOptions bench_odometry;
    BenchLabelOptions bench_label;
    BenchSessionsOptions bench_sessions;
    LabelOptions label;
    RunOptions run;
    TrainShapeOptions train_shape;
    BenchShapeOptions bench_shape;
    CompleteOptions complete;
    add_info(app, info);
    add_config(app, config);
    add_convert(app, convert);
    add_demo(app, demo);
    add_cad(app, cad);
    add_scene(app, scene);
    add_simulate(app, simulate);
    add_navigate(app, navigate);
    add_verify(app, verify);
    add_label(app, label);
    add_track(app, track, eval_tracking);
    add_detector(app, dataset, train_detector, detect, eval_detection);
    add_odometry(app, odometry);
    add_run(app, run);
    add_shape(app, train_shape, bench_shape, complete);
    add_bench(app, bench_sim, bench_nav, bench_merge, bench_verify, bench_track, bench_odometry,
              bench_label, bench_sessions, bench_shape);
    check_numbers(app);
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) known |= sub->get_name() == argv[1];
        if (!known) {
            print_error(std::string("unknown subcommand '") + argv[1] + "' (see makeway --help)");
            return kExitBadInput;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        print_error(e.what());
        return kExitBadInput;
    }
    try {
        std::vector<std::pair<std::string, std::string>> outputs, inputs;
        collect_paths(app, outputs, inputs);
        makeway::io::refuse_outputs_over_inputs(
            outputs, inputs);  // before any work: no output replaces an input
        const auto dispatch = [&]() -> int {
            if (app.got_subcommand("info")) return run_info(info);
            if (app.got_subcommand("config")) return run_config(config);
            if (app.got_subcommand("convert")) return run_convert(convert);
            if (app.got_subcommand("demo")) return run_demo(demo);
            if (app.got_subcommand("cad")) return run_cad(cad);
            if (app.got_subcommand("scene")) return run_scene(scene);
            if (app.got_subcommand("simulate")) return run_simulate(simulate);
            if (app.got_subcommand("navigate")) return run_navigate(navigate);
            if (app.got_subcommand("verify")) return run_verify(verify);
            if (app.got_subcommand("label")) return run_label(label);
            if (app.got_subcommand("track")) return run_track(track);
            if (app.got_subcommand("odometry")) return run_odometry(odometry);
            if (app.got_subcommand("run")) {
                if (run.clouds.empty() && run.bag.empty()) {
                    print_error("run: give --clouds DIR or --bag FILE");
                    return kExitBadInput;
                }
                return run_run(run);
            }
            if (app.got_subcommand("dataset")) return run_dataset(dataset);
            if (app.got_subcommand("train-detector")) return run_train_detector(train_detector);
            if (app.got_subcommand("detect")) return run_detect(detect);
            if (app.got_subcommand("eval-detection")) return run_eval_detection(eval_detection);
            if (app.got_subcommand("eval-tracking")) return run_eval_tracking(eval_tracking);
            if (app.got_subcommand("train-shape")) return run_train_shape(train_shape);
            if (app.got_subcommand("complete")) return run_complete(complete);
            if (app.got_subcommand("bench")) {
                const CLI::App* bench = app.get_subcommand("bench");
                if (bench->got_subcommand("nav")) return run_bench_nav(bench_nav);
                if (bench->got_subcommand("merge")) return run_bench_merge(bench_merge);
                if (bench->got_subcommand("verify")) return run_bench_verify(bench_verify);
                if (bench->got_subcommand("track")) return run_bench_track(bench_track);
                if (bench->got_subcommand("odometry")) return run_bench_odometry(bench_odometry);
                if (bench->got_subcommand("label")) return run_bench_label(bench_label);
                if (bench->got_subcommand("sessions")) return run_bench_sessions(bench_sessions);
                if (bench->got_subcommand("shape")) return run_bench_shape(bench_shape);
                return run_bench_sim(bench_sim);
            }
            return 1;
        };
        const int rc = dispatch();
        // A result that never reached its reader (a full disk, a closed pipe) is not a success.
        std::cout.flush();
        if (!std::cout || std::fflush(stdout) != 0) {
            print_error("standard output: write failed");
            return kExitBadInput;
        }
        return rc;
    } catch (const makeway::io::FileError& e) {
        print_error(e.what());
        return kExitBadInput;
    } catch (const makeway::io::Interrupted& e) {
        print_error(e.what());
        return e.exit_code();
    } catch (const std::exception& e) {
        const std::string what = e.what();
        print_error("internal error: " +
                    what.substr(0, what.find('\n')));  // one line (torch appends backtraces)
        return 1;
    }
    return 1;
}
