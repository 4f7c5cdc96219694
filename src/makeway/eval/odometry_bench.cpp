#include "makeway/eval/odometry_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "makeway/common/angles.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
OdometryDrive simulate_odometry_drive(const sim::Scene& scene, const sim::SequenceParams& params,
                                      int max_sweeps, const std::string& name) {
    const auto models = sim::models_of(scene);
    const sim::CollisionChecker checker(scene, models, params.robot);
    const auto route = sim::drive_route(scene, checker, params.robot);
    if (!route) throw std::runtime_error(name + ": no route through the scene");
    sim::SequenceSimulator simulator(scene, *route, params);
    OdometryDrive drive;
    drive.name = name;
    drive.start_pose = simulator.start_pose();
    std::vector<sim::SimFrame> frames;
    for (int i = 0; i <= max_sweeps && !simulator.reached_goal(); ++i)
        frames.push_back(simulator.next());
    // Sweep k ends where sweep k + 1 starts.
    for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
        const sim::SimFrame& f = frames[k];
        drive.sweeps.push_back({pipeline::sensor_channels_only(f.points_sensor), f.stamp_s,
                                frames[k + 1].stamp_s - f.stamp_s, f.odometry_pose,
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

TrajectoryMetrics trajectory_metrics(const std::vector<Pose2>& estimated,
                                     const std::vector<Pose2>& truth) {
    TrajectoryMetrics m;
    const std::size_t n = std::min(estimated.size(), truth.size());
    if (n == 0) return m;
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        sum_sq += std::pow(estimated[i].x_m - truth[i].x_m, 2) +
                  std::pow(estimated[i].y_m - truth[i].y_m, 2);
    }
    m.ate_rmse_m = std::sqrt(sum_sq / static_cast<double>(n));
    m.final_drift_m = std::hypot(estimated[n - 1].x_m - truth[n - 1].x_m,
                                 estimated[n - 1].y_m - truth[n - 1].y_m);
    std::vector<double> along(n, 0.0);
    for (std::size_t i = 1; i < n; ++i)
        along[i] = along[i - 1] +
                   std::hypot(truth[i].x_m - truth[i - 1].x_m, truth[i].y_m - truth[i - 1].y_m);
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
            const Pose2 e = between(estimated[i], estimated[j]);
            const Pose2 t = between(truth[i], truth[j]);
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
        const auto r = wheels ? odo.register_sweep(s.points_sensor, s.stamp_s, s.duration_s,
                                                   s.wheel_start, s.wheel_end)
                              : odo.register_sweep(s.points_sensor, s.stamp_s, s.duration_s,
                                                   std::nullopt, std::nullopt);
        run.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        run.poses.push_back(r.pose);
    }
    return run;
}

std::vector<OdometryDrive> benchmark_drives(int count, std::uint64_t seed,
                                            const sim::SequenceParams& params, int max_sweeps,
                                            const std::function<void(int)>& progress) {
    std::vector<OdometryDrive> drives;
    for (int i = 0; i < count; ++i) {
        sim::SequenceParams p = params;
        p.seed = seed + static_cast<std::uint64_t>(i);
        if (i % 5 == 4) {
            drives.push_back(simulate_odometry_drive(corridor_scene(), p, max_sweeps,
                                                     "corridor_" + std::to_string(p.seed)));
        } else {
            sim::SceneGenParams g;
            g.seed = p.seed;
            g.density = i % 2 == 0 ? sim::Density::kMedium : sim::Density::kDense;
            g.robot = params.robot;
            const sim::Scene scene = sim::generate_scene(g);
            drives.push_back(simulate_odometry_drive(scene, p, max_sweeps, scene.name));
        }
        if (progress) progress(i + 1);
    }
    return drives;
}

std::vector<Pose2> dead_reckoning(const OdometryDrive& drive) {
    std::vector<Pose2> out;
    Pose2 pose = drive.start_pose;
    for (const auto& s : drive.sweeps) {
        pose = compose(pose, between(s.wheel_start, s.wheel_end));
        out.push_back(pose);
    }
    return out;
}

std::vector<Pose2> truth_of(const OdometryDrive& drive) {
    std::vector<Pose2> out;
    for (const auto& s : drive.sweeps) out.push_back(s.true_end);
    return out;
}

std::string odometry_table_markdown(const std::vector<OdometryScore>& scores,
                                    const std::vector<std::string>& methods) {
    const auto fmt = [](double v, int digits) {
        char b[32];
        std::snprintf(b, sizeof(b), "%.*f", digits, v);
        return std::string(b);
    };
    std::string t =
        "| method | ATE RMSE mean [cm] | ATE worst [cm] | RPE 1 m [%] | RPE 5 m [%] | RPE 5 m "
        "[deg/m] | final drift mean [cm] | sweeps/s (1 core) |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const std::string& m : methods) {
        double ate = 0, worst = 0, r1 = 0, r5 = 0, r5d = 0, drift = 0, sps = 0;
        int n = 0;
        for (const auto& s : scores) {
            if (s.method != m) continue;
            ++n;
            ate += s.metrics.ate_rmse_m;
            worst = std::max(worst, s.metrics.ate_rmse_m);
            r1 += s.metrics.rpe_1m_percent;
            r5 += s.metrics.rpe_5m_percent;
            r5d += s.metrics.rpe_5m_deg_per_m;
            drift += s.metrics.final_drift_m;
            sps += s.sweeps_per_second;
        }
        if (n == 0) continue;
        t += "| " + m + " | " + fmt(100 * ate / n, 2) + " | " + fmt(100 * worst, 2) + " | " +
             fmt(r1 / n, 2) + " | " + fmt(r5 / n, 2) + " | " + fmt(r5d / n, 3) + " | " +
             fmt(100 * drift / n, 1) + " | " + (sps > 0 ? fmt(sps / n, 0) : std::string("-")) +
             " |\n";
    }
    t += "\n| drive | length [m] |";
    for (const auto& m : methods) t += " " + m + " ATE [cm] |";
    t += "\n| --- | --- |";
    for (std::size_t k = 0; k < methods.size(); ++k) t += " --- |";
    t += "\n";
    std::vector<std::string> drives;
    for (const auto& s : scores) {
        if (std::find(drives.begin(), drives.end(), s.drive) == drives.end())
            drives.push_back(s.drive);
    }
    for (const auto& d : drives) {
        std::string row = "| " + d + " |";
        double length = 0;
        std::string cells;
        for (const auto& m : methods) {
            std::string cell = " - |";
            for (const auto& s : scores) {
                if (s.drive == d && s.method == m) {
                    cell = " " + fmt(100 * s.metrics.ate_rmse_m, 2) + " |";
                    length = s.metrics.length_m;
                }
            }
            cells += cell;
        }
        t += row + " " + fmt(length, 1) + " |" + cells + "\n";
    }
    return t;
}

}  // namespace makeway::eval
