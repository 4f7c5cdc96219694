// LiDAR odometry fused with wheel odometry (issue 15) on simulated drives, with the truth kept
// apart for scoring.
#include <gtest/gtest.h>

#include <cmath>

#include "makeway/eval/odometry_bench.hpp"
#include "makeway/odometry/lidar_odometry.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::odometry {
namespace {

using eval::dead_reckoning;
using eval::truth_of;

TEST(LidarOdometry, ShortDriveStaysNearTheTruth) {
    sim::SceneGenParams g;
    g.seed = 4;
    g.density = sim::Density::kDense;
    const sim::Scene scene = sim::generate_scene(g);
    sim::SequenceParams p;
    p.seed = 4;
    const eval::OdometryDrive drive = eval::simulate_odometry_drive(scene, p, 250, "dense_4");
    ASSERT_GT(drive.length_m, 10.0);
    const auto run = eval::run_makeway_odometry(drive, OdometryParams{}, p.robot.T_robot_sensor());
    const auto ours = eval::trajectory_metrics(run.poses, truth_of(drive));
    const auto wheels = eval::trajectory_metrics(dead_reckoning(drive), truth_of(drive));
    std::cout << "[          ] " << drive.sweeps.size() << " sweeps, " << drive.length_m << " m: ATE " << ours.ate_rmse_m
              << " m (wheels " << wheels.ate_rmse_m << "), RPE 5 m " << ours.rpe_5m_percent << " % (wheels "
              << wheels.rpe_5m_percent << "), " << drive.sweeps.size() / run.seconds << " sweeps/s\n";
    EXPECT_LT(ours.ate_rmse_m, 0.03);
    EXPECT_LT(ours.ate_rmse_m, wheels.ate_rmse_m);
}

TEST(LidarOdometry, CorridorDoesNotCollapseAndAWalkerDoesNotJerkThePose) {
    const sim::Scene scene = eval::corridor_scene();
    sim::SequenceParams p;
    p.seed = 2;
    const eval::OdometryDrive drive = eval::simulate_odometry_drive(scene, p, 400, "corridor");
    ASSERT_GT(drive.length_m, 20.0);
    const auto truth = truth_of(drive);
    const auto run = eval::run_makeway_odometry(drive, OdometryParams{}, p.robot.T_robot_sensor());
    const auto ours = eval::trajectory_metrics(run.poses, truth);
    const auto wheels = eval::trajectory_metrics(dead_reckoning(drive), truth);
    // Along the corridor the walls say nothing: the estimate must follow the wheels there, not
    // stick to the wall samples (a collapse shortens the drive) nor slide.
    double est_len = 0.0;
    for (std::size_t i = 1; i < run.poses.size(); ++i) est_len += std::hypot(run.poses[i].x_m - run.poses[i - 1].x_m, run.poses[i].y_m - run.poses[i - 1].y_m);
    // Sweep-to-sweep change of the error once under way (the first 2 s settle the threshold): the
    // walker comes down the corridor and passes within a metre of the sensor about 16 s in.
    double max_jump = 0.0;
    for (std::size_t i = 20; i < truth.size(); ++i) {
        const Pose2 e = between(truth[i], run.poses[i]), e0 = between(truth[i - 1], run.poses[i - 1]);
        max_jump = std::max(max_jump, std::hypot(e.x_m - e0.x_m, e.y_m - e0.y_m));
    }
    std::cout << "[          ] corridor " << drive.length_m << " m (estimated " << est_len << " m): ATE " << ours.ate_rmse_m
              << " m (wheels " << wheels.ate_rmse_m << "), final " << ours.final_drift_m << " m, largest jump " << max_jump << " m\n";
    EXPECT_NEAR(est_len / drive.length_m, 1.0, 0.02);
    EXPECT_LT(ours.final_drift_m, std::max(0.1, 1.5 * wheels.final_drift_m));
    EXPECT_LT(max_jump, 0.02);
}

}  // namespace
}  // namespace makeway::odometry
