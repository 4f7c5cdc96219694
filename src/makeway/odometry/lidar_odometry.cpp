#include "makeway/odometry/lidar_odometry.hpp"

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "makeway/common/angles.hpp"
#include "makeway/common/handover.hpp"
#include "makeway/common/voxel_thin.hpp"
#include "makeway/odometry/param_tables.hpp"

namespace makeway::odometry {
namespace {

// Rotation's effect counted at this lever [m] when comparing poses (convergence, deviations).
constexpr double kLever_m = 1.0;
// A map plane whose normal is this close to vertical is a floor or ceiling.
constexpr double kHorizontal = 0.8;
// A map line whose direction is this close to vertical is a leg, a frame or a corner.
constexpr double kVertical = 0.9;
// Deviations remembered for the adaptive threshold.
constexpr std::size_t kDeviationWindow = 100;
// Fewer points than this stay on the caller's thread (a parallel loop's start costs more).
constexpr std::size_t kParallelPoints = 8192, kParallelSource = 512;

double sq(double v) { return v * v; }

// One source point's say in a Gauss-Newton step: the Jacobian row of its residual and the residual.
struct Contribution {
    Eigen::Vector3d row = Eigen::Vector3d::Zero();
    double r = 0.0;
    bool used = false;
};

}  // namespace

struct LidarOdometry::Threads {
    explicit Threads(int n) : arena(n) {}
    tbb::task_arena arena;
};

std::vector<std::string> OdometryParams::validate() const {
    std::vector<std::string> p = odometry_table().problems(*this);
    if (map.min_points_for_plane < 3) p.push_back("min_points_for_plane must be >= 3");
    return p;
}

LidarOdometry::LidarOdometry(const OdometryParams& params, const Isometry3& T_base_sensor,
                             const Pose2& start_pose)
    : params_(params), T_base_sensor_(T_base_sensor), pose_(start_pose), map_(params.map) {
    throw_if_problems(params.validate(), "lidar odometry");
    if (params_.threads > 1) threads_ = std::make_shared<Threads>(params_.threads);
}

OdometryResult LidarOdometry::register_sweep(const PointCloud& points_sensor, double /*stamp_s*/,
                                             double duration_s,
                                             const std::optional<Pose2>& wheel_start,
                                             const std::optional<Pose2>& wheel_end) {
    // 1. Prediction: the wheels' motion over the sweep (and over any gap since the last one), else
    // the last sweep's motion again.
    Pose2 gap, motion = last_motion_;
    if (wheel_start && wheel_end) {
        if (last_wheel_end_) gap = between(*last_wheel_end_, *wheel_start);
        motion = between(*wheel_start, *wheel_end);
        last_wheel_end_ = wheel_end;
    }
    const Pose2 predicted_start = compose(pose_, gap);
    const Pose2 predicted = compose(predicted_start, motion);

    // 2. De-skewing into the base frame at the sweep's end; range and floor filters.
    const bool timed =
        params_.deskew && points_sensor.time_s.size() == points_sensor.size() && duration_s > 0.0;
    const Isometry3 T_end_start = lift_to_3d(motion).inverse();
    // A spinning sensor fires a column of beams at once: consecutive points share their time, and
    // the motion at that time is computed once per column (1,800 a sweep, not 57,600). On several
    // threads the sweep is cut into runs of points, each de-skewed alone and joined in order.
    const auto deskew = [&](std::size_t begin, std::size_t end,
                            std::vector<Eigen::Vector3d>& into) {
        into.reserve(end - begin);
        float column_time = -1.0f;
        Isometry3 T_end_point = T_end_start;
        for (std::size_t i = begin; i < end; ++i) {
            const Eigen::Vector3d p = points_sensor.xyz[i].cast<double>();
            if (!p.allFinite()) continue;
            const double range = p.norm();
            if (range < params_.min_range_m || range > params_.max_range_m) continue;
            const Eigen::Vector3d p_base = T_base_sensor_ * p;
            if (p_base.z() < params_.min_height_m) continue;
            if (timed) {
                if (points_sensor.time_s[i] != column_time) {
                    column_time = points_sensor.time_s[i];
                    const double s =
                        std::clamp(static_cast<double>(column_time) / duration_s, 0.0, 1.0);
                    T_end_point = T_end_start * lift_to_3d(interpolate(Pose2{}, motion, s));
                }
                into.push_back(T_end_point * p_base);
            } else {
                into.push_back(T_end_start *
                               p_base);  // an instantaneous sweep, taken at its stamp (the start)
            }
        }
    };
    std::vector<Eigen::Vector3d> points;
    const std::size_t n = points_sensor.size();
    if (threads_ && n >= kParallelPoints) {
        std::vector<std::vector<Eigen::Vector3d>> runs(static_cast<std::size_t>(params_.threads));
        visible_parallel_for(threads_->arena, tbb::blocked_range<std::size_t>(0, runs.size(), 1),
                             [&](const tbb::blocked_range<std::size_t>& part) {
                                 for (std::size_t k = part.begin(); k != part.end(); ++k)
                                     deskew(k * n / runs.size(), (k + 1) * n / runs.size(),
                                            runs[k]);
                             });
        points.reserve(n);
        for (const auto& run : runs) points.insert(points.end(), run.begin(), run.end());
    } else {
        deskew(0, n, points);
    }
    // The map's share of the sweep (one point per insert voxel) is thinned on another thread while
    // this one registers the sweep.
    std::vector<Eigen::Vector3d> insert;
    Handover thinned;
    tbb::task_group thinning;
    const auto thin_for_map = [&] { insert = voxel_thin(points, params_.insert_voxel_m); };
    if (threads_) {
        thinned.release();
        threads_->arena.execute([&] {
            thinning.run([&] {
                thinned.acquire();
                thin_for_map();
                thinned.release();
            });
        });
    } else {
        thin_for_map();
    }

    OdometryResult out;
    Pose2 estimate = predicted;
    const double threshold =
        deviations_.size() < 5
            ? params_.initial_threshold_m
            : std::clamp(
                  3.0 * std::sqrt(std::accumulate(deviations_.begin(), deviations_.end(), 0.0,
                                                  [](double a, double d) { return a + d * d; }) /
                                  static_cast<double>(deviations_.size())),
                  params_.min_threshold_m, params_.max_threshold_m);
    out.threshold_m = threshold;
    if (!first_ && !map_.empty()) {
        // 3. Planar Gauss-Newton with the wheel prior.
        const std::vector<Eigen::Vector3d> source = voxel_thin(points, params_.source_voxel_m);
        out.source_points = source.size();
        const double travelled = std::hypot(motion.x_m, motion.y_m) + std::hypot(gap.x_m, gap.y_m);
        const double turned = std::abs(motion.yaw_rad) + std::abs(gap.yaw_rad);
        const double sigma_t = params_.wheel_sigma_m + params_.wheel_sigma_per_m * travelled;
        const double sigma_r = params_.wheel_sigma_rad + params_.wheel_sigma_per_rad * turned;
        const Eigen::Vector3d prior_info(1.0 / sq(sigma_t), 1.0 / sq(sigma_t), 1.0 / sq(sigma_r));
        const double kernel = sq(threshold / 3.0);
        const double inv_var = 1.0 / sq(params_.residual_sigma_m);
        Eigen::Matrix3d H_lidar = Eigen::Matrix3d::Zero();
        std::vector<Contribution> contributions(source.size());
        for (int it = 0; it < params_.max_iterations; ++it) {
            const double c = std::cos(estimate.yaw_rad), s = std::sin(estimate.yaw_rad);
            Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
            Eigen::Vector3d g = Eigen::Vector3d::Zero();
            // The correspondences (the nearest-point searches: most of a sweep's registration)
            // on every thread the odometry has, then their sum in the points' order: the same
            // floating-point result whatever the thread count.
            const auto contribute = [&](std::size_t i) {
                const Eigen::Vector3d& p = source[i];
                Contribution& out_i = contributions[i];
                out_i.used = false;
                const Eigen::Vector2d rp(c * p.x() - s * p.y(), s * p.x() + c * p.y());
                const Eigen::Vector3d q(rp.x() + estimate.x_m, rp.y() + estimate.y_m, p.z());
                const auto m = map_.nearest(q, threshold);
                if (!m) return;
                const Eigen::Vector3d d = q - m->point;
                // Point-to-plane on walls and faces, point-to-line on legs, door frames and wall
                // corners (vertical lines). Residuals run
                // only across the structure, so nothing holds the pose to old samples along a wall
                // (a corridor). Left out: floors and ceilings (no say in planar motion), blobs
                // (corners of planes, clutter: no direction to trust) and other lines, which
                // indoors are mostly one scan ring crossing a wall, a sampling pattern that moves
                // with the robot.
                Eigen::Matrix3d J =
                    Eigen::Matrix3d::Zero();  // d(q) / d(x, y, yaw); z does not move
                J << 1.0, 0.0, -rp.y(), 0.0, 1.0, rp.x(), 0.0, 0.0, 0.0;
                if (m->shape == VoxelShape::kPlane && std::abs(m->axis.z()) < kHorizontal) {
                    out_i.row = J.transpose() * m->axis;
                    out_i.r = m->axis.dot(d);
                } else if (m->shape == VoxelShape::kLine && std::abs(m->axis.z()) > kVertical) {
                    // Across the line of sight only: a wall seen edge-on fills a voxel with one
                    // firing's column of returns, a "line" that slides along the wall (nearly the
                    // line of sight) as the robot moves; taken whole, those columns held the pose
                    // back by 13 cm in the first second of the benchmark's corridor.
                    const Eigen::Vector3d across =
                        Eigen::Vector3d(estimate.y_m - q.y(), q.x() - estimate.x_m, 0.0)
                            .normalized();
                    out_i.row = J.transpose() * across;
                    out_i.r = across.dot(d);
                } else {
                    return;
                }
                out_i.used = true;
            };
            if (threads_ && source.size() >= kParallelSource) {
                visible_parallel_for(threads_->arena,
                                     tbb::blocked_range<std::size_t>(0, source.size(), 256),
                                     [&](const tbb::blocked_range<std::size_t>& part) {
                                         for (std::size_t i = part.begin(); i != part.end(); ++i)
                                             contribute(i);
                                     });
            } else {
                for (std::size_t i = 0; i < source.size(); ++i) contribute(i);
            }
            std::size_t matched = 0;
            for (const Contribution& k : contributions) {
                if (!k.used) continue;
                const double w = sq(kernel) / sq(kernel + k.r * k.r) * inv_var;
                H.noalias() += w * k.row * k.row.transpose();
                g.noalias() += w * k.row * k.r;
                ++matched;
            }
            H_lidar = H;
            out.correspondences = matched;
            const Eigen::Vector3d prior_r(estimate.x_m - predicted.x_m,
                                          estimate.y_m - predicted.y_m,
                                          angle_diff(estimate.yaw_rad, predicted.yaw_rad));
            H += prior_info.asDiagonal();
            g += prior_info.cwiseProduct(prior_r);
            const Eigen::Vector3d step = -H.ldlt().solve(g);
            if (!step.allFinite()) break;
            estimate.x_m += step.x();
            estimate.y_m += step.y();
            estimate.yaw_rad = wrap_angle(estimate.yaw_rad + step.z());
            out.iterations = it + 1;
            if (step.head<2>().norm() + kLever_m * std::abs(step.z()) < params_.convergence_m)
                break;
        }
        const Eigen::Vector3d ev =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(H_lidar).eigenvalues();
        out.constraint_ratio = ev(2) > 0.0 ? std::max(ev(0), 0.0) / ev(2) : 0.0;
        // The adaptive threshold: how far registration moved the prediction (KISS-ICP's model
        // deviation, with the rotation counted at the sensor's useful range).
        const double deviation =
            std::hypot(estimate.x_m - predicted.x_m, estimate.y_m - predicted.y_m) +
            10.0 * std::abs(angle_diff(estimate.yaw_rad, predicted.yaw_rad));
        deviations_.push_back(deviation);
        if (deviations_.size() > kDeviationWindow) deviations_.erase(deviations_.begin());
    }
    first_ = false;

    // 4. The map: the registered sweep in, far voxels out.
    if (threads_) {
        threads_->arena.execute([&] { thinning.wait(); });
        thinned.acquire();
    }
    const double c = std::cos(estimate.yaw_rad), s = std::sin(estimate.yaw_rad);
    std::vector<Eigen::Vector3d> world = std::move(insert);
    for (auto& p : world)
        p = Eigen::Vector3d(c * p.x() - s * p.y() + estimate.x_m,
                            s * p.x() + c * p.y() + estimate.y_m, p.z());
    map_.add(world);
    map_.keep_within(Eigen::Vector3d(estimate.x_m, estimate.y_m, 0.0), params_.map_radius_m);

    last_motion_ = between(pose_, estimate);
    pose_ = estimate;
    const Pose2 start = compose(estimate, between(motion, Pose2{}));
    out.pose = estimate;
    out.T_world_sensor_end = lift_to_3d(estimate) * T_base_sensor_;
    out.T_world_sensor_start = lift_to_3d(start) * T_base_sensor_;
    return out;
}

}  // namespace makeway::odometry
