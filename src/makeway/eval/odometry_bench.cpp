#include "makeway/eval/odometry_bench.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "makeway/common/angles.hpp"
#include "makeway/sim/route.hpp"

namespace makeway::eval {
namespace {

// The points as the sensor gives them: no labels, no instance ids.
PointCloud sensor_channels(const PointCloud& c) {
    PointCloud out;
    out.xyz = c.xyz;
    out.intensity = c.intensity;
    out.ring = c.ring;
    out.time_s = c.time_s;
    return out;
}

}  // namespace

OdometryDrive simulate_odometry_drive(const sim::Scene& scene, const sim::SequenceParams& params, int max_sweeps,
                                      const std::string& name) {
    const auto models = sim::models_of(scene);
    const sim::CollisionChecker checker(scene, models, params.robot);
    const auto route = sim::drive_route(scene, checker, params.robot);
    if (!route) throw std::runtime_error(name + ": no route through the scene");
    sim::SequenceSimulator simulator(scene, *route, params);
    OdometryDrive drive;
    drive.name = name;
    drive.start_pose = simulator.start_pose();
    std::vector<sim::SimFrame> frames;
    for (int i = 0; i <= max_sweeps && !simulator.reached_goal(); ++i) frames.push_back(simulator.next());
    // Sweep k ends where sweep k + 1 starts.
    for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
        const sim::SimFrame& f = frames[k];
        drive.sweeps.push_back({sensor_channels(f.points_sensor), f.stamp_s, frames[k + 1].stamp_s - f.stamp_s, f.odometry_pose,
                                f.odometry_end_pose, frames[k + 1].true_pose});
        const Pose2& a = f.true_pose;
        const Pose2& b = frames[k + 1].true_pose;
        drive.length_m += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    }
    return drive;
}

sim::Scene corridor_scene(double length_m, double width_m) {
    sim::Scene s;
    s.name = "corridor";
    s.density = "corridor";
    const double x0 = -length_m / 2, x1 = length_m / 2, y = width_m / 2;
    s.floor_min_m = Eigen::Vector2d(x0 - 0.5, -y - 0.5);
    s.floor_max_m = Eigen::Vector2d(x1 + 0.5, y + 0.5);
    s.walls = {{{x0, -y}, {x1, -y}}, {{x0, y}, {x1, y}}, {{x0, -y}, {x0, y}}, {{x1, -y}, {x1, y}}};
    s.walkers.push_back({{{x1 - 1.0, 0.4}, {x0 + 1.0, 0.4}}, 1.0, 0.0});
    s.start = {x0 + 1.0, -0.3, 0.0};
    s.waypoint = {0.0, -0.3, 0.0};
    s.goal = {x1 - 1.0, -0.3, 0.0};
    return s;
}

TrajectoryMetrics trajectory_metrics(const std::vector<Pose2>& estimated, const std::vector<Pose2>& truth) {
    TrajectoryMetrics m;
    const std::size_t n = std::min(estimated.size(), truth.size());
    if (n == 0) return m;
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        sum_sq += std::pow(estimated[i].x_m - truth[i].x_m, 2) + std::pow(estimated[i].y_m - truth[i].y_m, 2);
    }
    m.ate_rmse_m = std::sqrt(sum_sq / static_cast<double>(n));
    m.final_drift_m = std::hypot(estimated[n - 1].x_m - truth[n - 1].x_m, estimated[n - 1].y_m - truth[n - 1].y_m);
    std::vector<double> along(n, 0.0);
    for (std::size_t i = 1; i < n; ++i) along[i] = along[i - 1] + std::hypot(truth[i].x_m - truth[i - 1].x_m, truth[i].y_m - truth[i - 1].y_m);
    m.length_m = along[n - 1];
    const auto rpe = [&](double d, double& percent, double& deg_per_m) {
        double t_sum = 0.0, r_sum = 0.0;
        int pairs = 0;
        std::size_t j = 0;
        for (std::size_t i = 0; i < n; ++i) {
            j = std::max(j, i);
            while (j < n && along[j] - along[i] < d) ++j;
            if (j >= n) break;
            const double dist = along[j] - along[i];
            const Pose2 e = odometry::between(estimated[i], estimated[j]);
            const Pose2 t = odometry::between(truth[i], truth[j]);
            t_sum += std::hypot(e.x_m - t.x_m, e.y_m - t.y_m) / dist;
            r_sum += std::abs(angle_diff(e.yaw_rad, t.yaw_rad)) * 180.0 / M_PI / dist;
            ++pairs;
        }
        percent = pairs ? 100.0 * t_sum / pairs : 0.0;
        deg_per_m = pairs ? r_sum / pairs : 0.0;
    };
    rpe(1.0, m.rpe_1m_percent, m.rpe_1m_deg_per_m);
    rpe(5.0, m.rpe_5m_percent, m.rpe_5m_deg_per_m);
    return m;
}

OdometryRun run_makeway_odometry(const OdometryDrive& drive, const odometry::OdometryParams& params,
                                 const Isometry3& T_base_sensor, bool wheels) {
    OdometryRun run;
    odometry::LidarOdometry odo(params, T_base_sensor, drive.start_pose);
    for (const OdometrySweep& s : drive.sweeps) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto r = wheels ? odo.register_sweep(s.points_sensor, s.stamp_s, s.duration_s, s.wheel_start, s.wheel_end)
                              : odo.register_sweep(s.points_sensor, s.stamp_s, s.duration_s, std::nullopt, std::nullopt);
        run.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        run.poses.push_back(r.pose);
    }
    return run;
}

}  // namespace makeway::eval
