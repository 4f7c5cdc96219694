#include "makeway/sim/robot.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "makeway/common/angles.hpp"
#include "makeway/sim/param_tables.hpp"

namespace makeway::sim {
namespace {

double approach(double current, double target, double max_step) {
    return current + std::clamp(target - current, -max_step, max_step);
}

// Points on a rectangle's outline (centre, size, yaw) every spacing_m.
void add_rectangle_outline(std::vector<Eigen::Vector2d>& out, const Eigen::Vector2d& centre,
                           const Eigen::Vector2d& size, double yaw, double spacing_m) {
    const Eigen::Rotation2Dd R(yaw);
    const Eigen::Vector2d h = 0.5 * size;
    const Eigen::Vector2d corners[4] = {
        {-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}};
    for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % 4];
        const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing_m)));
        for (int i = 0; i < n; ++i)
            out.push_back(centre + R * (a + (b - a) * (static_cast<double>(i) / n)));
    }
}

}  // namespace

std::vector<Eigen::Vector2d> low_surface_points(const TriangleMesh& mesh, const BodyHeights& body,
                                                double spacing_m) {
    std::set<std::pair<long, long>> seen;
    std::vector<Eigen::Vector2d> out;
    auto keep = [&](const Eigen::Vector3d& p) {
        if (!body.can_hit(p.z())) return;
        const auto key = std::make_pair(std::lround(p.x() / (0.5 * spacing_m)),
                                        std::lround(p.y() / (0.5 * spacing_m)));
        if (seen.insert(key).second) out.emplace_back(p.x(), p.y());
    };
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices_m[t[0]].cast<double>();
        const Eigen::Vector3d b = mesh.vertices_m[t[1]].cast<double>();
        const Eigen::Vector3d c = mesh.vertices_m[t[2]].cast<double>();
        if (std::min({a.z(), b.z(), c.z()}) > body.top_m ||
            std::max({a.z(), b.z(), c.z()}) < body.ground_clearance_m)
            continue;
        const double longest = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
        const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing_m)));
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; i + j <= n; ++j) {
                keep(a + (b - a) * (static_cast<double>(i) / n) +
                     (c - a) * (static_cast<double>(j) / n));
            }
        }
    }
    return out;
}

bool robot_caused_contact(const Pose2& pose, double v, double w,
                          const Eigen::Vector2d& contact_world, double length_m, double width_m,
                          double threshold) {
    return speed_toward_contact(pose, v, w, contact_world, length_m, width_m) > threshold;
}

double speed_toward_contact(const Pose2& pose, double v, double w,
                            const Eigen::Vector2d& contact_world, double length_m, double width_m) {
    const Eigen::Vector2d r = to_isometry(pose).inverse() * contact_world;  // robot frame
    // The outward normal of the side nearest the contact (the point lies in or on the footprint).
    const double to_front = 0.5 * length_m - std::abs(r.x()),
                 to_side = 0.5 * width_m - std::abs(r.y());
    const Eigen::Vector2d normal = to_front <= to_side
                                       ? Eigen::Vector2d(r.x() >= 0.0 ? 1.0 : -1.0, 0.0)
                                       : Eigen::Vector2d(0.0, r.y() >= 0.0 ? 1.0 : -1.0);
    const Eigen::Vector2d body_velocity(v - w * r.y(), w * r.x());  // v x-hat + w z-hat x r
    return body_velocity.dot(normal);
}

RobotState step_diff_drive(const RobotState& state, const VelocityCommand& command, double dt_s,
                           const RobotParams& params) {
    RobotState next = state;
    const double v_target = std::clamp(command.v_mps, -params.max_v_mps, params.max_v_mps);
    const double w_target = std::clamp(command.w_radps, -params.max_w_radps, params.max_w_radps);
    next.v_mps = approach(state.v_mps, v_target, params.max_acc_mps2 * dt_s);
    next.w_radps = approach(state.w_radps, w_target, params.max_ang_acc_radps2 * dt_s);
    // Exact integration of a constant-velocity arc over dt.
    const double th = state.pose.yaw_rad, v = next.v_mps, w = next.w_radps;
    if (std::abs(w) < 1e-9) {
        next.pose.x_m += v * dt_s * std::cos(th);
        next.pose.y_m += v * dt_s * std::sin(th);
    } else {
        next.pose.x_m += v / w * (std::sin(th + w * dt_s) - std::sin(th));
        next.pose.y_m -= v / w * (std::cos(th + w * dt_s) - std::cos(th));
    }
    next.pose.yaw_rad = wrap_angle(th + w * dt_s);
    return next;
}

std::vector<std::string> OdometryNoiseParams::validate() const {
    return wheel_noise_table().problems(*this);
}

WheelOdometry::WheelOdometry(const Pose2& start, const OdometryNoiseParams& params,
                             std::uint64_t seed)
    : pose_(start), params_(params), rng_(make_rng(seed, 7)) {}

void WheelOdometry::update(const Pose2& before, const Pose2& after) {
    // The true increment in the robot frame, then noise scaled by how far it moved and turned.
    const Isometry2 delta = to_isometry(before).inverse() * to_isometry(after);
    const Pose2 d = to_pose2(delta);
    const double dist = std::hypot(d.x_m, d.y_m);
    // Random-walk drift: the variance of each error grows linearly with distance and angle.
    const double dist_error = normal(rng_, 0.0, params_.translation_noise_per_m * std::sqrt(dist));
    const double scale = dist > 1e-12 ? 1.0 + dist_error / dist : 1.0;
    const double yaw_sigma = std::sqrt(
        params_.heading_noise_per_rad * params_.heading_noise_per_rad * std::abs(d.yaw_rad) +
        params_.heading_noise_per_m * params_.heading_noise_per_m * dist);
    const double dyaw = d.yaw_rad + normal(rng_, 0.0, yaw_sigma);
    const Pose2 noisy{d.x_m * scale, d.y_m * scale, dyaw};
    pose_ = to_pose2(to_isometry(pose_) * to_isometry(noisy));
}

CollisionChecker::CollisionChecker(const Scene& scene, const std::vector<ObjectModel>& models,
                                   const RobotParams& robot, double spacing_m)
    : scene_(scene), robot_(robot) {
    for (const Wall& w : scene.walls) {
        const Eigen::Vector2d d = w.b_m - w.a_m;
        add_rectangle_outline(static_points_, 0.5 * (w.a_m + w.b_m),
                              Eigen::Vector2d(d.norm() + w.thickness_m, w.thickness_m),
                              std::atan2(d.y(), d.x()), spacing_m);
    }
    for (const Pillar& p : scene.pillars)
        add_rectangle_outline(static_points_, p.centre_m, p.size_m, 0.0, spacing_m);
    for (const EnvironmentMesh& e : scene.environment) {
        if (!e.mesh_world) continue;
        for (const auto& q : low_surface_points(*e.mesh_world, robot.body(), spacing_m))
            static_points_.push_back(q);
    }
    for (const ObjectModel& m : models) {
        object_points_.push_back(low_surface_points(m.mesh_object, robot.body(), spacing_m));
        double r = 0.0;
        for (const auto& p : object_points_.back()) r = std::max(r, p.norm());
        object_radius_m_.push_back(r);
    }
}

template <typename Fn>
void CollisionChecker::for_each_point_near(const Eigen::Vector2d& centre, double radius, double t_s,
                                           Fn&& fn, Against against) const {
    if (against != Against::kPeople) {
        if (against != Against::kFurniture) {
            for (const auto& p : static_points_) {
                if ((p - centre).squaredNorm() <= radius * radius) fn(p);
            }
        }
        for (std::size_t i = 0; against != Against::kStructure && i < object_points_.size(); ++i) {
            const Pose2 pose = object_pose_at(scene_, i, t_s);
            const Eigen::Vector2d c(pose.x_m, pose.y_m);
            if ((c - centre).norm() > radius + object_radius_m_[i]) continue;
            const Isometry2 T = to_isometry(pose);
            for (const auto& p : object_points_[i]) fn(T * p);
        }
    }
    if (against != Against::kEverything && against != Against::kPeople) return;
    for (const Walker& w : scene_.walkers) {
        const Eigen::Vector2d c = walker_position_at(w, t_s);
        if ((c - centre).norm() > radius + kPersonRadius_m) continue;
        for (int k = 0; k < 24; ++k) {
            const double a = 2.0 * kPi * k / 24;
            fn(c + kPersonRadius_m * Eigen::Vector2d(std::cos(a), std::sin(a)));
        }
    }
}

bool CollisionChecker::collides(const Pose2& pose, double t_s, Against against) const {
    const Isometry2 T_robot_world = to_isometry(pose).inverse();
    const double hl = 0.5 * robot_.length_m, hw = 0.5 * robot_.width_m;
    bool inside = false;
    for_each_point_near(
        Eigen::Vector2d(pose.x_m, pose.y_m), robot_.circumscribed_radius_m() + 1e-9, t_s,
        [&](const Eigen::Vector2d& p_world) {
            const Eigen::Vector2d p = T_robot_world * p_world;
            inside |= std::abs(p.x()) <= hl && std::abs(p.y()) <= hw;
        },
        against);
    return inside;
}

std::optional<Eigen::Vector2d> CollisionChecker::contact_point(const Pose2& pose, double t_s,
                                                               Against against) const {
    const Isometry2 T_robot_world = to_isometry(pose).inverse();
    const double hl = 0.5 * robot_.length_m, hw = 0.5 * robot_.width_m;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int n = 0;
    for_each_point_near(
        Eigen::Vector2d(pose.x_m, pose.y_m), robot_.circumscribed_radius_m() + 1e-9, t_s,
        [&](const Eigen::Vector2d& p_world) {
            const Eigen::Vector2d p = T_robot_world * p_world;
            if (std::abs(p.x()) <= hl && std::abs(p.y()) <= hw) sum += p_world, ++n;
        },
        against);
    if (n == 0) return std::nullopt;
    return Eigen::Vector2d(sum / n);
}

double CollisionChecker::clearance_m(const Pose2& pose, double t_s, double max_m) const {
    const Isometry2 T_robot_world = to_isometry(pose).inverse();
    const double hl = 0.5 * robot_.length_m, hw = 0.5 * robot_.width_m;
    double best = max_m;
    bool inside = false;
    for_each_point_near(Eigen::Vector2d(pose.x_m, pose.y_m),
                        robot_.circumscribed_radius_m() + max_m + 1e-9, t_s,
                        [&](const Eigen::Vector2d& p_world) {
                            const Eigen::Vector2d p = T_robot_world * p_world;
                            const double dx = std::max(std::abs(p.x()) - hl, 0.0);
                            const double dy = std::max(std::abs(p.y()) - hw, 0.0);
                            if (dx == 0.0 && dy == 0.0) inside = true;
                            best = std::min(best, std::hypot(dx, dy));
                        });
    return inside ? 0.0 : best;
}

std::vector<Eigen::Vector2d> CollisionChecker::obstacle_points(double t_s) const {
    std::vector<Eigen::Vector2d> out;
    for_each_point_near(Eigen::Vector2d::Zero(), 1e9, t_s,
                        [&](const Eigen::Vector2d& p) { out.push_back(p); });
    return out;
}

}  // namespace makeway::sim
