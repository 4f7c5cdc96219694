// The odometry benchmark side by side: makeway's LiDAR odometry (fused with the wheels), KISS-ICP
// 1.2.3 (MIT, built here from its sources, never into the library or the program) and the wheel
// odometry alone, on the very same simulated sweeps, one core each (TBB limited to one thread).
//
//   build/bin/compare_kiss_icp [--scenes 10] [--seed 0] [--max-sweeps 600] [--out DIR]
//
// KISS-ICP gets its defaults with the same range limits as makeway (0.5-40 m), voxel size by its
// rule max_range / 100 (0.4 m), an indoor adaptive threshold (below), its constant-velocity
// prediction (it takes no wheel odometry) and the sweeps' per-point times for its de-skewing.
// Both start at the robot's start pose. KISS-ICP runs twice: on the sweeps as they are, and with
// the floor's returns removed as makeway's odometry does.
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "kiss_icp/pipeline/KissICP.hpp"
#include "makeway/eval/odometry_bench.hpp"

namespace {

using namespace makeway;

// `floor_removed`: only points at least min_height_m above the base, the filter makeway's own
// odometry applies (KISS-ICP registers every point, and indoors the floor's scan rings, which move
// with the robot, are a large share of a sweep).
eval::OdometryRun run_kiss_icp(const eval::OdometryDrive& drive, const Isometry3& T_base_sensor,
                               bool floor_removed) {
    const double min_height_m = makeway::odometry::OdometryParams{}.min_height_m;
    kiss_icp::pipeline::KISSConfig config;
    config.max_range = 40.0;
    config.min_range = 0.5;
    config.voxel_size = config.max_range / 100.0;
    // Its defaults are set for cars (1 m per sweep): with min_motion_th 0.1 m a robot's few-cm
    // deviations never update the adaptive threshold, which then stays at initial_threshold (2 m).
    // Indoors it gets makeway's initial threshold and deviations counted from 1 cm.
    config.initial_threshold = 0.5;
    config.min_motion_th = 0.01;
    config.max_num_threads = 1;
    kiss_icp::pipeline::KissICP kiss(config);
    // KISS-ICP's poses are the sensor at each sweep's end, from the first sweep's end (the robot
    // stands still there: the start pose).
    const Isometry3 T_world_first = lift_to_3d(drive.start_pose) * T_base_sensor;
    eval::OdometryRun run;
    std::vector<Eigen::Vector3d> frame;
    std::vector<double> stamps;
    for (const auto& s : drive.sweeps) {
        frame.clear();
        stamps.clear();
        for (std::size_t i = 0; i < s.points_sensor.size(); ++i) {
            if (floor_removed &&
                (T_base_sensor * s.points_sensor.xyz[i].cast<double>()).z() < min_height_m)
                continue;
            frame.push_back(s.points_sensor.xyz[i].cast<double>());
            stamps.push_back(s.points_sensor.time_s[i]);
        }
        const auto t0 = std::chrono::steady_clock::now();
        kiss.RegisterFrame(frame, stamps);
        run.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        Isometry3 T_first_sensor;
        T_first_sensor.matrix() = kiss.pose().matrix();
        run.poses.push_back(
            project_to_plane(T_world_first * T_first_sensor * T_base_sensor.inverse()));
    }
    return run;
}

}  // namespace

int main(int argc, char** argv) {
    int scenes = 10, max_sweeps = 600;
    std::uint64_t seed = 0;
    std::string out = "out/compare_kiss_icp_side_by_side";
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--scenes")
            scenes = std::atoi(value.c_str());
        else if (key == "--seed")
            seed = std::strtoull(value.c_str(), nullptr, 10);
        else if (key == "--max-sweeps")
            max_sweeps = std::atoi(value.c_str());
        else if (key == "--out")
            out = value;
        else {
            std::cerr << "compare_kiss_icp: unknown option " << key << "\n";
            return 2;
        }
    }
    if (scenes < 1 || max_sweeps < 10) {
        std::cerr << "compare_kiss_icp: --scenes >= 1 and --max-sweeps >= 10\n";
        return 2;
    }
    const tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
    const sim::SequenceParams seq;
    std::cerr << "simulating " << scenes << " drives...\n";
    const auto drives = eval::benchmark_drives(scenes, seed, seq, max_sweeps);
    std::vector<eval::OdometryScore> scores;
    for (const auto& d : drives) {
        const auto truth = eval::truth_of(d);
        const auto ours = eval::run_makeway_odometry(d, {}, seq.robot.T_robot_sensor());
        const auto kiss = run_kiss_icp(d, seq.robot.T_robot_sensor(), false);
        const auto kiss_nf = run_kiss_icp(d, seq.robot.T_robot_sensor(), true);
        const double n = static_cast<double>(d.sweeps.size());
        scores.push_back(
            {d.name, "makeway", eval::trajectory_metrics(ours.poses, truth), n / ours.seconds});
        scores.push_back(
            {d.name, "KISS-ICP", eval::trajectory_metrics(kiss.poses, truth), n / kiss.seconds});
        scores.push_back({d.name, "KISS-ICP, floor removed",
                          eval::trajectory_metrics(kiss_nf.poses, truth), n / kiss_nf.seconds});
        scores.push_back(
            {d.name, "wheels", eval::trajectory_metrics(eval::dead_reckoning(d), truth), 0.0});
        std::cerr << d.name << ": makeway " << scores[scores.size() - 4].metrics.ate_rmse_m
                  << " m, KISS-ICP " << scores[scores.size() - 3].metrics.ate_rmse_m
                  << " m, floor removed " << scores[scores.size() - 2].metrics.ate_rmse_m << " m\n";
    }
    const std::string table =
        "# Odometry side by side: " + std::to_string(drives.size()) + " drives, seed " +
        std::to_string(seed) + " (build/bin/compare_kiss_icp)\n\n" +
        eval::odometry_table_markdown(scores,
                                      {"makeway", "KISS-ICP", "KISS-ICP, floor removed", "wheels"});
    std::filesystem::create_directories(out);
    std::ofstream(std::filesystem::path(out) / "table.md") << table;
    std::cout << table;
    return 0;
}
