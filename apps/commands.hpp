#pragma once
// One function per subcommand. main.cpp alone parses the command line (CLI11 is slow to compile)
// and fills these option structs. Each returns the process exit code: 0 success, 2 bad input.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace makeway::apps {

constexpr int kExitBadInput = 2;

struct InfoOptions {
    std::string path;
};
int run_info(const InfoOptions& options);

struct ConfigOptions {
    std::string file;       ///< empty: the built-in defaults
    bool describe = false;  ///< each key's value, admitted values, unit and doc instead of YAML
};
int run_config(const ConfigOptions& options);

struct ConvertOptions {
    std::string input;
    std::string output;
    std::string pcd_encoding = "binary";
    std::string ply_encoding = "binary";
    std::string non_finite = "reject";
};
int run_convert(const ConvertOptions& options);

struct DemoOptions {
    std::string config;  ///< empty: built-in defaults
    std::string out_dir = "out/demo";
};
int run_demo(const DemoOptions& options);

/// Prints "makeway: MESSAGE" to stderr.
void print_error(const std::string& message);

}  // namespace makeway::apps

namespace makeway::apps {

struct CadOptions {
    std::string style;
    std::uint64_t seed = 0;
    std::string out;
};
int run_cad(const CadOptions& options);

struct SceneOptions {
    std::uint64_t seed = 0;
    std::string density = "medium";
    std::string layout = "random";
    int sessions = 1;
    bool no_people = false;
    std::string out = "scene.yaml";
};
int run_scene(const SceneOptions& options);

struct SimulateOptions {
    std::string config;  ///< lidar, robot and odometry sections; empty: built-in defaults
    std::string scene;
    std::string route = "auto";
    int frames = 100;
    std::string out_dir;
    std::string format = "pcd";
    std::uint64_t seed = 0;
    int threads = 1;
    bool allow_outside_paths = false;  ///< the scene's meshes may lie outside its folder
};
int run_simulate(const SimulateOptions& options);

struct BenchSimOptions {
    std::uint64_t seed = 0;
    int sweeps = 20;
    std::string out;  ///< optional JSON file
};
int run_bench_sim(const BenchSimOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct NavigateOptions {
    std::string config;  ///< lidar, robot and affordance sections; empty: built-in defaults
    std::string scene;
    std::string method = "gt-perc";
    std::string map;    ///< optional map_server YAML for the static layer
    std::string model;  ///< detector weights for `ours`; empty: the default ones
    std::string out_dir;
    std::uint64_t seed = 0;
    double time_limit_s = 180.0;
    bool allow_outside_paths = false;  ///< the scene's meshes may lie outside its folder
};
int run_navigate(const NavigateOptions& options);

struct BenchNavOptions {
    std::string config;
    int scenes = 25;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_nav";
    std::string model;  ///< detector weights for `ours`; empty: the default ones when present
    int threads = 2;
    double time_limit_s = 180.0;
    std::vector<std::string> methods;  ///< empty: every method (ours when weights are there)
    std::string shard;  ///< "K/N": run scenes K, K + N, ... and write partial.json (empty: every
                        ///< scene, the results)
    std::string layout =
        "random";  ///< random (densities cycle) or study_space (the paper's room, seeded)
    std::string shape_model;  ///< `ours` verifies against these learned shapes instead of the
                              ///< scenes' CAD models
};
int run_bench_nav(const BenchNavOptions& options);
/// "K/N" with 0 <= K < N, or nullopt.
std::optional<std::pair<int, int>> parse_shard(const std::string& text);

struct BenchMergeOptions {
    std::vector<std::string> dirs;  ///< folders holding partial.json (one per shard)
    std::string out_dir = "out/bench_nav";
};
/// Joins `bench nav --shard` partials into exactly what the unsharded run writes.
int run_bench_merge(const BenchMergeOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct BenchVerifyOptions {
    int scenes = 5;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_verify";
    double min_yaw_margin = 0.0;  ///< VerifyParams::min_yaw_margin
    double approx_e_max_m = 0.0;  ///< VerifyParams::approx_e_max_m
};
int run_bench_verify(const BenchVerifyOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct VerifyOptions {
    std::string cloud;
    std::string detections;
    std::string cad_dir;
    std::string out;
    std::string non_finite = "reject";  ///< as detect: NaN points are bad input unless dropped
};
int run_verify(const VerifyOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct TrackOptions {
    std::string detections;  ///< folder of per-frame JSON (makeway) or KITTI file / folder of files
    std::string format = "makeway";
    std::string poses;   ///< TUM sensor poses per frame (makeway format, optional)
    std::string config;  ///< YAML; its tracking section (default: built-in, KITTI preset for kitti)
    double rate_hz = 10.0;  ///< frame rate for KITTI files (stamps = frame / rate)
    std::optional<double> range_m, min_score;
    std::vector<std::string>
        classes;  ///< empty: every class in the input (kitti), chair and table (makeway)
    std::string score_transform = "auto";  ///< auto, none or sigmoid
    std::string out_of_range;              ///< freeze or drop; empty: the configuration's
    double fov_deg = 0.0;  ///< > 0: KITTI output only within this horizontal field of view
    std::string output_score = "detection";  ///< kitti: detection, existence or track-mean
    bool coasting = false;    ///< kitti: boxes of confirmed tracks not detected in the frame, every
                              ///< type (default: the type's preset)
    int coasting_frames = 0;  ///< kitti, with coasting: at most this many frames after the last
                              ///< detection (0: until dropped)
    bool no_coasting = false;  ///< kitti: no such boxes for any type
    bool backfill = true;      ///< kitti: a confirmed track's output starts at its first detection
    std::string out;
};
int run_track(const TrackOptions& options);

struct EvalTrackingOptions {
    std::string gt;
    std::string tracks;
    std::string format = "makeway";
    std::vector<std::string> classes;  ///< kitti: classes evaluated (default: those in the tracks)
    double min_iou = 0.25;             ///< kitti: 3D IoU of a match
    double fov_deg = 0.0;              ///< kitti: > 0 scores only this horizontal field of view
    bool devkit_rounding = false;      ///< kitti: AB3DMOT's script's re-averaged scores, to the bit
    std::string out;                   ///< optional JSON
};
int run_eval_tracking(const EvalTrackingOptions& options);

struct BenchTrackOptions {
    std::string config;  ///< YAML whose tracking section replaces the defaults (empty: none)
    bool scan_occlusion = false;
    int scenes = 5;
    std::uint64_t seed = 0;
    std::string out_dir = "out/bench_track";
};
int run_bench_track(const BenchTrackOptions& options);

struct OdometryOptions {
    std::string clouds;    ///< folder of sweeps (.pcd/.ply/.bin), in name order
    std::string odometry;  ///< optional TUM wheel odometry, one pose per sweep start
    std::string config;    ///< lidar_odometry and robot (mount) sections
    std::vector<double> start{0.0, 0.0, 0.0};  ///< x, y, yaw of the base at the first sweep
    double rate_hz = 10.0;                     ///< sweep rate without odometry stamps
    std::string out;
};
int run_odometry(const OdometryOptions& options);

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
int run_run(const RunOptions& options);

struct BenchOdometryOptions {
    std::string config;
    int scenes = 10;
    std::uint64_t seed = 0;
    int max_sweeps = 600;
    std::string out_dir = "out/bench_odometry";
};
int run_bench_odometry(const BenchOdometryOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct DatasetOptions {
    int scenes = 20;
    std::uint64_t seed = 0;
    std::vector<std::string> exclude_styles{"armchair", "round_table"};
    int keyframe_every = 10;
    int max_keyframes = 30;
    bool all_styles = false;  ///< every style of the simulator, not only the seven scenes draw from
    std::string
        furniture;  ///< a folder of the user's own furniture meshes (io/furniture_folder.hpp)
    double furniture_share = 0.5;
    std::string out;
};
int run_dataset(const DatasetOptions& options);

struct TrainDetectorOptions {
    std::vector<std::string> data;
    int epochs = 20;
    int batch = 8;
    double learning_rate = 2e-3;
    std::uint64_t seed = 0;
    int threads = 0;
    int width = 32;
    bool intensity = false;
    bool resume = false;
    std::string out;
};
int run_train_detector(const TrainDetectorOptions& options);

struct DetectOptions {
    std::string model;  ///< empty: the default weights
    std::string cloud;
    std::string non_finite =
        "reject";  ///< points with NaN/inf coordinates: reject the file or drop them
    std::string out;
};
int run_detect(const DetectOptions& options);

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
};
int run_eval_detection(const EvalDetectionOptions& options);

}  // namespace makeway::apps

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
int run_label(const LabelOptions& options);

struct BenchLabelOptions {
    int scenes = 10;
    int sessions = 3;
    std::uint64_t seed = 0;
    int max_sweeps = 600;
    bool no_cad = false;
    std::string out_dir = "out/bench_label";
};
int run_bench_label(const BenchLabelOptions& options);

struct BenchSessionsOptions {
    std::string model;  ///< the detector to start from (default weights when empty)
    int rounds = 2;
    int scenes_per_round = 4;
    int sessions = 3;
    int max_sweeps = 300;
    int epochs = 6;
    int eval_scenes = 3;
    int replay_scenes = 16;
    int threads = 2;
    std::uint64_t seed = 0;
    std::vector<std::string> left_out_styles{"armchair", "round_table", "lounge_chair",
                                             "pedestal_table"};
    std::string out_dir = "out/bench_sessions";
};
int run_bench_sessions(const BenchSessionsOptions& options);

}  // namespace makeway::apps

namespace makeway::apps {

struct TrainShapeOptions {
    int scenes = 24;
    std::uint64_t seed = 0;
    std::vector<std::string> exclude_styles{"armchair", "round_table"};
    double steps_scale = 1.0;  ///< every stage's step count times this
    int threads = 2;
    std::string out = "models/shape.pt";
};
int run_train_shape(const TrainShapeOptions& options);

struct BenchShapeOptions {
    std::string model;  ///< empty: models/shape.pt
    int scenes = 6;
    std::uint64_t seed = 1000;
    std::vector<std::string> left_out{"armchair", "round_table"};
    int threads = 1;
    double inlier_distance = 0.05;  ///< the robust solve's inlier residual [m]
    int hypotheses = 0;  ///< the robust solve's minimal samples (0: the weighted solve alone)
    bool pose_only = false;
    std::string out_dir = "out/bench_shape";
};
int run_bench_shape(const BenchShapeOptions& options);

struct CompleteOptions {
    std::string model;  ///< empty: models/shape.pt
    std::string cloud;
    std::string box;  ///< "cx,cy,cz,length,width,height,yaw" in the cloud's frame
    std::string cls;
    std::string sensor = "0,0,0";  ///< where the returns were seen from, in the cloud's frame
    std::string out;
};
int run_complete(const CompleteOptions& options);

}  // namespace makeway::apps
