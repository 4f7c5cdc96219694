#pragma once
// The odometry benchmark's parts: simulated drives as a robot records them (label-free sweeps with
// per-point time, drifting wheel odometry, the truth kept apart for scoring), a corridor scene,
// the trajectory metrics (ATE, RPE over 1 m and 5 m) and makeway's odometry run over a drive.
// `makeway bench odometry` and the side-by-side program bench/bench_odometry (KISS-ICP) share them.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/odometry/lidar_odometry.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {

struct OdometrySweep {
    PointCloud points_sensor;  ///< x, y, z, intensity, ring, time: what the sensor gives
    double stamp_s = 0.0, duration_s = 0.1;
    Pose2 wheel_start, wheel_end;  ///< drifting wheel odometry
    Pose2 true_end;                ///< scoring only: the base at the sweep's end
};

struct OdometryDrive {
    std::string name;
    Pose2 start_pose;  ///< the base at the first sweep's start (what a robot is told)
    std::vector<OdometrySweep> sweeps;
    double length_m = 0.0;
};

/// Drives the scene's auto route (start -> waypoint -> goal) for at most `max_sweeps` sweeps.
/// Throws std::runtime_error when the scene has no route.
OdometryDrive simulate_odometry_drive(const sim::Scene& scene, const sim::SequenceParams& params,
                                      int max_sweeps, const std::string& name);

/// A straight corridor `length_m` x `width_m` with smooth walls (degenerate along its axis for
/// LiDAR registration), a person walking its length, start at one end, goal at the other.
sim::Scene corridor_scene(double length_m = 30.0, double width_m = 2.2);

struct TrajectoryMetrics {
    double ate_rmse_m = 0.0;     ///< RMSE of position errors (both start at the true start pose)
    double final_drift_m = 0.0;  ///< position error at the end
    double rpe_1m_percent = 0.0, rpe_1m_deg_per_m = 0.0;
    double rpe_5m_percent = 0.0, rpe_5m_deg_per_m = 0.0;
    double length_m = 0.0;
};
/// Poses one per sweep end, same length. RPE pairs every pose with the first one at least d metres
/// of true path further on; drives shorter than d give 0.
TrajectoryMetrics trajectory_metrics(const std::vector<Pose2>& estimated,
                                     const std::vector<Pose2>& truth);

struct OdometryRun {
    std::vector<Pose2> poses;  ///< the base at each sweep's end
    double seconds = 0.0;      ///< registration time, all sweeps
};
/// makeway's odometry over the drive; `wheels` false: constant-velocity prediction only.
OdometryRun run_makeway_odometry(const OdometryDrive& drive, const odometry::OdometryParams& params,
                                 const Isometry3& T_base_sensor, bool wheels = true);

/// The benchmark's drives: medium and dense generated scenes with walkers and chairs being pulled
/// (seeds seed, seed + 1, ...), every fifth a corridor. `progress(done)` after each drive.
std::vector<OdometryDrive> benchmark_drives(int count, std::uint64_t seed,
                                            const sim::SequenceParams& params, int max_sweeps,
                                            const std::function<void(int)>& progress = {});

/// The wheel odometry alone, integrated from the start pose (the baseline every method must beat).
std::vector<Pose2> dead_reckoning(const OdometryDrive& drive);
/// The truth at every sweep's end.
std::vector<Pose2> truth_of(const OdometryDrive& drive);

/// One method on one drive, scored.
struct OdometryScore {
    std::string drive, method;
    TrajectoryMetrics metrics;
    double sweeps_per_second = 0.0;  ///< 0 when not timed (the wheels)
};
/// A markdown table: per method, the mean and worst ATE, mean RPE and sweeps per second, and one
/// row per drive.
std::string odometry_table_markdown(const std::vector<OdometryScore>& scores,
                                    const std::vector<std::string>& methods);

}  // namespace makeway::eval
