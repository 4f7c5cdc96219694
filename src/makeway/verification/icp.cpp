#include "makeway/verification/icp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/angles.hpp"

namespace makeway::verification {

Isometry3 Pose4::matrix() const { return make_T_xyz_yaw(t_m, yaw_rad); }

std::vector<std::string> IcpParams::validate(std::size_t levels) const {
    std::vector<std::string> p;
    if (iterations.size() != levels || max_correspondence_m.size() != levels) {
        p.push_back("iterations and max_correspondence_m need one entry per CAD level (" +
                    std::to_string(levels) + ")");
    }
    for (double d : max_correspondence_m) {
        if (!(d > 0.0 && d < 5.0)) p.push_back("max_correspondence_m must be in (0, 5)");
    }
    if (!(cauchy_scale_m > 0.0)) p.push_back("cauchy_scale_m must be > 0");
    return p;
}

LevelledSegment thin_to_levels(const std::vector<Eigen::Vector3d>& segment, const CadModel& model) {
    LevelledSegment out;
    for (const ModelLevel& level : model.levels)
        out.per_level_sensor.push_back(voxel_thin(segment, level.voxel_m));
    return out;
}

IcpResult align(const std::vector<Eigen::Vector3d>& segment, const CadModel& model,
                const Pose4& initial, const IcpParams& params, int first_level, int last_level) {
    return align(thin_to_levels(segment, model), model, initial, params, first_level, last_level);
}

double geometric_residual(const std::vector<Eigen::Vector3d>& seg, const CadModel& model, int level,
                          const Pose4& pose, double max_corr, double keep_fraction) {
    if (seg.empty()) return max_corr;
    const ModelLevel& m = model.levels[static_cast<std::size_t>(level)];
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    std::vector<double> r2;
    r2.reserve(seg.size());
    for (const auto& p : seg) {
        const Eigen::Vector3d d = p - pose.t_m;
        const Eigen::Vector3d q(c * d.x() + s * d.y(), -s * d.x() + c * d.y(),
                                d.z());  // R^T (p - t)
        double d2 = 0.0;
        const std::size_t j = m.nearest(q, max_corr, &d2);
        const double r = j == ModelLevel::kNone
                             ? max_corr
                             : std::abs(m.normals_object[j].dot(q - m.points_object[j]));
        r2.push_back(std::min(r * r, max_corr * max_corr));
    }
    // Trimmed: the worst points are often other objects inside the enlarged box.
    const auto keep =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(keep_fraction * r2.size())));
    std::nth_element(r2.begin(), r2.begin() + static_cast<long>(keep - 1), r2.end());
    double sum = 0.0;
    for (std::size_t i = 0; i < keep; ++i) sum += r2[i];
    return std::sqrt(sum / static_cast<double>(keep));
}

IcpResult align(const LevelledSegment& segment, const CadModel& model, const Pose4& initial,
                const IcpParams& params, int first_level, int last_level,
                FinalResidual final_residual) {
    IcpResult result;
    result.pose = initial;
    const int n_levels = static_cast<int>(model.levels.size());
    if (last_level < 0 || last_level >= n_levels) last_level = n_levels - 1;
    if (segment.per_level_sensor.size() != model.levels.size() || first_level < 0) {
        result.residual_m = std::numeric_limits<double>::infinity();  // thinned for another library
        return result;
    }
    for (int level = first_level; level <= last_level; ++level) {
        const ModelLevel& m = model.levels[static_cast<std::size_t>(level)];
        // The robust scale follows the level: coarse levels tolerate coarse residuals.
        const double c = std::max(params.cauchy_scale_m, m.voxel_m);
        const double inv_c2 = 1.0 / (c * c);
        const std::vector<Eigen::Vector3d>& seg =
            segment.per_level_sensor[static_cast<std::size_t>(level)];
        const double max_corr = params.max_correspondence_m[static_cast<std::size_t>(level)];
        result.converged = false;
        // The coarsest level only steers the pose toward the finer ones (and is most of the calls:
        // every model's four yaw candidates run it before ranking): its correspondences are the
        // point held by the query's grid cell, one read, at most two cell diagonals farther than
        // the nearest (measured up to 7 cm at its 4 cm cells; its robust scale is 8 cm). Finer
        // levels, where the candidates are ranked and the winner fitted, and every residual take
        // the exact nearest of the 8 surrounding cells: the 4 cm level by one cell too lost yaw
        // flips in tests/verification (84 deg off with injected outliers).
        const bool exact = level != 0;
        for (int it = 0; it < params.iterations[static_cast<std::size_t>(level)]; ++it) {
            ++result.iterations;
            Pose4& x = result.pose;
            const double cy = std::cos(x.yaw_rad), s = std::sin(x.yaw_rad);
            Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
            Eigen::Vector4d g = Eigen::Vector4d::Zero();
            int used = 0;
            for (const auto& p : seg) {
                const Eigen::Vector3d d = p - x.t_m;
                const Eigen::Vector3d q(cy * d.x() + s * d.y(), -s * d.x() + cy * d.y(), d.z());
                double d2 = 0.0;
                const std::size_t j =
                    exact ? m.nearest(q, max_corr, &d2) : m.nearest_cell(q, max_corr, &d2);
                if (j == ModelLevel::kNone) continue;
                const Eigen::Vector3d& n = m.normals_object[j];
                const double r = n.dot(q - m.points_object[j]);  // eq. (1), in the object frame
                // q = R^T (p - t): dq/dt = -R^T, dq/dyaw = dR^T/dyaw (p - t).
                const Eigen::Vector3d Rn(cy * n.x() - s * n.y(), s * n.x() + cy * n.y(), n.z());
                const Eigen::Vector3d dq_dyaw(-s * d.x() + cy * d.y(), -cy * d.x() - s * d.y(),
                                              0.0);
                Eigen::Vector4d J;
                J << -Rn, n.dot(dq_dyaw);
                const double w =
                    1.0 / (1.0 + r * r * inv_c2);  // Cauchy: rho(r) = c^2/2 log(1 + r^2/c^2)
                H += w * J * J.transpose();
                g += w * J * r;
                ++used;
            }
            if (used < 4) break;
            const double wz = params.z_prior_weight * used;  // the z prior (see IcpParams)
            H(2, 2) += wz;
            g(2) += wz * (x.t_m.z() - initial.t_m.z());
            H.diagonal().array() += 1e-9;
            const Eigen::Vector4d delta = -H.ldlt().solve(g);
            if (!delta.allFinite()) break;
            x.t_m += delta.head<3>();
            x.yaw_rad = wrap_angle(x.yaw_rad + delta[3]);
            if (delta.head<3>().norm() < params.convergence_m &&
                std::abs(delta[3]) < params.convergence_rad) {
                result.converged = true;
                break;
            }
        }
    }
    if (final_residual == FinalResidual::kSkip) {
        result.residual_m = std::numeric_limits<double>::quiet_NaN();
        return result;
    }
    result.residual_m = geometric_residual(
        segment.per_level_sensor[static_cast<std::size_t>(last_level)], model, last_level,
        result.pose, params.max_correspondence_m[static_cast<std::size_t>(last_level)],
        params.residual_keep_fraction);
    return result;
}

}  // namespace makeway::verification
