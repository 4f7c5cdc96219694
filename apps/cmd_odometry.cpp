// makeway odometry / makeway bench odometry: LiDAR odometry fused with wheel odometry on recorded
// sweeps, and its benchmark on simulated drives (KISS-ICP side by side:
// build/bin/compare_kiss_icp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/sim_config.hpp"
#include "io/staged_output.hpp"
#include "makeway/eval/odometry_bench.hpp"
#include "makeway/odometry/lidar_odometry.hpp"

namespace makeway::apps {

struct OdometryOptions {
    std::string clouds;    ///< folder of sweeps (.pcd/.ply/.bin), in name order
    std::string odometry;  ///< optional TUM wheel odometry, one pose per sweep start
    std::string config;    ///< lidar_odometry and robot (mount) sections
    std::vector<double> start{0.0, 0.0, 0.0};  ///< x, y, yaw of the base at the first sweep
    double rate_hz = 10.0;                     ///< sweep rate without odometry stamps
    std::string out;
};

struct BenchOdometryOptions {
    std::string config;
    int scenes = 10;
    std::uint64_t seed = 0;
    int max_sweeps = 600;
    std::string out_dir = "out/bench_odometry";
};

namespace fs = std::filesystem;

int run_odometry(const OdometryOptions& o) {
    const io::Config cfg = io::load_config(o.config);
    const std::vector<fs::path> files = io::sweep_files(o.clouds);
    std::vector<io::StampedPose> wheels;
    if (!o.odometry.empty()) {
        wheels = io::read_tum(o.odometry);
        if (wheels.size() < files.size()) {
            throw io::FileError(o.odometry, "holds " + std::to_string(wheels.size()) +
                                                " poses for " + std::to_string(files.size()) +
                                                " sweeps");
        }
    }
    if (const std::string p = io::start_problem(o.start); !p.empty())
        throw io::FileError("--start", p);
    const Pose2 start{o.start[0], o.start[1], o.start[2]};
    odometry::LidarOdometry odo(cfg.system.lidar_odometry, cfg.robot.T_robot_sensor(), start);
    std::vector<io::StampedPose> out;
    io::ProgressBar bar("odometry", files.size());
    double seconds = 0.0;
    bool timed = true;
    for (std::size_t k = 0; k < files.size(); ++k) {
        const PointCloud cloud = io::read_point_cloud(files[k]).cloud;
        timed &= cloud.time_s.size() == cloud.size();
        const double stamp =
            wheels.empty() ? static_cast<double>(k) / o.rate_hz : wheels[k].stamp_s;
        const double next = k + 1 < wheels.size() ? wheels[k + 1].stamp_s : stamp + 1.0 / o.rate_hz;
        std::optional<Pose2> wheel_start, wheel_end;
        if (k + 1 < wheels.size()) {  // the last sweep: constant velocity
            wheel_start = project_to_plane(wheels[k].T_world_sensor);
            wheel_end = project_to_plane(wheels[k + 1].T_world_sensor);
        }
        const auto t0 = std::chrono::steady_clock::now();
        const auto r =
            odo.register_sweep(cloud, stamp, std::max(next - stamp, 1e-3), wheel_start, wheel_end);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        out.push_back({stamp, r.T_world_sensor_start});
        bar.update(k + 1, std::to_string(cloud.size()) + " points");
    }
    bar.finish();
    io::write_tum(o.out, out);
    std::cout << "wrote " << out.size() << " sensor poses (sweep starts) to " << o.out << ": "
              << static_cast<int>(static_cast<double>(files.size()) / std::max(seconds, 1e-9))
              << " sweeps per second"
              << (o.odometry.empty() ? ", no wheel odometry (constant velocity)" : "")
              << (timed ? "" : ", sweeps without per-point time (not de-skewed)") << "\n";
    return 0;
}

int run_bench_odometry(const BenchOdometryOptions& o) {
    const io::SimConfig cfg = io::load_sim_config(o.config);
    sim::SequenceParams seq;
    seq.lidar = cfg.lidar;
    seq.robot = cfg.robot;
    seq.odometry = cfg.odometry;
    io::ProgressBar sim_bar("simulate drives", static_cast<std::size_t>(o.scenes));
    const auto drives = eval::benchmark_drives(o.scenes, o.seed, seq, o.max_sweeps, [&](int d) {
        sim_bar.update(static_cast<std::size_t>(d));
    });
    sim_bar.finish();
    std::vector<eval::OdometryScore> scores;
    io::ProgressBar bar("odometry", drives.size());
    std::size_t sweeps = 0;
    for (const auto& d : drives) {
        const auto truth = eval::truth_of(d);
        const auto run =
            eval::run_makeway_odometry(d, cfg.system.lidar_odometry, seq.robot.T_robot_sensor());
        scores.push_back({d.name, "makeway", eval::trajectory_metrics(run.poses, truth),
                          static_cast<double>(d.sweeps.size()) / run.seconds});
        scores.push_back(
            {d.name, "wheels", eval::trajectory_metrics(eval::dead_reckoning(d), truth), 0.0});
        sweeps += d.sweeps.size();
        bar.update(scores.size() / 2, d.name);
    }
    bar.finish();
    const std::vector<std::string> methods{"makeway", "wheels"};
    const std::string table = "# Odometry benchmark: " + std::to_string(drives.size()) +
                              " drives, " + std::to_string(sweeps) + " sweeps, seed " +
                              std::to_string(o.seed) + "\n\n" +
                              eval::odometry_table_markdown(scores, methods) +
                              "\nKISS-ICP on the same sweeps, side by side: "
                              "build/bin/compare_kiss_icp (built when its sources are "
                              "available, see README).\n";
    io::Json runs = io::Json::array();
    for (const auto& s : scores) {
        runs.push_back({{"drive", s.drive},
                        {"method", s.method},
                        {"ate_rmse_m", s.metrics.ate_rmse_m},
                        {"final_drift_m", s.metrics.final_drift_m},
                        {"rpe_1m_percent", s.metrics.rpe_1m_percent},
                        {"rpe_1m_deg_per_m", s.metrics.rpe_1m_deg_per_m},
                        {"rpe_5m_percent", s.metrics.rpe_5m_percent},
                        {"rpe_5m_deg_per_m", s.metrics.rpe_5m_deg_per_m},
                        {"length_m", s.metrics.length_m},
                        {"sweeps_per_second", s.sweeps_per_second}});
    }
    io::StagedOutput staged(o.out_dir);
    io::write_json(staged.staging() / "summary.json",
                   {{"drives", drives.size()}, {"seed", o.seed}, {"runs", runs}});
    io::write_file_atomic(staged.staging() / "table.md", table);
    staged.commit();
    std::cout << table;
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_odometry(CommandSpec& c, OdometryOptions& o) {
    c.option("--clouds", o.clouds,
             "Folder of sweeps (.pcd with a time/t field, .ply, .bin), taken in name order")
        .required();
    c.option("--odometry", o.odometry,
             "Wheel odometry (TUM, one base pose per sweep start, its stamps the sweeps'); "
             "without it: constant velocity");
    c.option("--config", o.config,
             "YAML configuration: lidar_odometry and robot (sensor mount) sections");
    c.option("--start", o.start, "The base's pose at the first sweep: x y yaw [m, m, rad]")
        .expected(3)
        .show_default();
    c.option("--rate", o.rate_hz, "Sweeps per second without odometry stamps")
        .range(0.1, 100.0)
        .show_default();
    c.option("--out", o.out, "Poses (TUM: stamp x y z qx qy qz qw)").required();
}
const Registration<OdometryOptions> kOdometry{
    "odometry", Group::kRecordedData,
    "LiDAR odometry fused with wheel odometry on recorded sweeps (per-point "
    "time de-skews them); writes the sensor pose at each sweep's start (TUM)",
    declare_odometry, run_odometry};

void declare_bench_odometry(CommandSpec& c, BenchOdometryOptions& odo_o) {
    c.option("--config", odo_o.config,
             "YAML configuration: lidar, robot, wheel_noise and lidar_odometry sections");
    c.option("--scenes", odo_o.scenes, "Drives (every fifth a corridor)")
        .range(1, 1000)
        .show_default();
    c.option("--seed", odo_o.seed, "Seed of scenes, sensor noise and wheel drift").show_default();
    c.option("--max-sweeps", odo_o.max_sweeps, "Sweeps per drive at most")
        .range(10, 100000)
        .show_default();
    c.option("--out", odo_o.out_dir, "Output folder (summary.json, table.md)").show_default();
}
const Registration<BenchOdometryOptions> kBenchOdometry{
    "bench odometry", Group::kEvaluation,
    "LiDAR odometry on simulated drives (medium and dense scenes with people "
    "and pulled chairs, corridors): ATE, RPE over 1 m and 5 m, sweeps per second; "
    "writes summary.json and table.md",
    declare_bench_odometry, run_bench_odometry};

}  // namespace

}  // namespace makeway::apps
