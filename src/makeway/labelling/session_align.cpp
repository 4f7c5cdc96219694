#include "makeway/labelling/session_align.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/voxel_thin.hpp"

namespace makeway::labelling {

std::vector<std::string> SessionAlignParams::validate() const {
    std::vector<std::string> e;
    if (!(voxel_m > 0.0)) e.push_back("labelling.align.voxel_m must be > 0");
    if (iterations < 1) e.push_back("labelling.align.iterations must be >= 1");
    if (max_distance_m.empty())
        e.push_back("labelling.align.max_distance_m needs at least one stage");
    for (double d : max_distance_m) {
        if (!(d > 0.0)) e.push_back("labelling.align.max_distance_m must be > 0");
    }
    if (!(cauchy_scale_m > 0.0) || !(inlier_m > 0.0))
        e.push_back("labelling.align.cauchy_scale_m and inlier_m must be > 0");
    return e;
}

namespace {

// The residual of one point and its 1x3 Jacobian in (x, y, yaw) applied on the left: a plane
// match gives one point-to-plane row, anything else up to three point-to-point rows.
struct Row {
    double r;
    Eigen::RowVector3d J;
};

void rows_of(const Eigen::Vector3d& p, const odometry::MapMatch& m, std::vector<Row>& out) {
    const Eigen::Vector3d dp_dyaw(-p.y(), p.x(), 0.0);
    auto add = [&](const Eigen::Vector3d& n) {
        out.push_back({n.dot(p - m.point), Eigen::RowVector3d(n.x(), n.y(), n.dot(dp_dyaw))});
    };
    if (m.shape == odometry::VoxelShape::kPlane) {
        add(m.axis);
    } else {
        add(Eigen::Vector3d::UnitX());
        add(Eigen::Vector3d::UnitY());
    }
}

}  // namespace

SessionAlignment align_session(const odometry::VoxelMap& reference,
                               const std::vector<Eigen::Vector3d>& session_map,
                               const SessionAlignParams& params, const Isometry3& initial) {
    SessionAlignment out;
    Isometry3 T = initial;
    const std::vector<Eigen::Vector3d> points = voxel_thin(session_map, params.voxel_m);
    std::vector<Row> rows;
    const int per_stage =
        std::max(1, params.iterations / static_cast<int>(params.max_distance_m.size()));
    for (double max_d : params.max_distance_m) {
        for (int it = 0; it < per_stage; ++it) {
            ++out.iterations;
            Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
            Eigen::Vector3d g = Eigen::Vector3d::Zero();
            for (const Eigen::Vector3d& q : points) {
                const Eigen::Vector3d p = T * q;
                const std::optional<odometry::MapMatch> m = reference.nearest(p, max_d);
                if (!m) continue;
                rows.clear();
                rows_of(p, *m, rows);
                for (const Row& row : rows) {
                    const double c = params.cauchy_scale_m;
                    const double w = 1.0 / (1.0 + (row.r / c) * (row.r / c));
                    H += w * row.J.transpose() * row.J;
                    g += w * row.J.transpose() * row.r;
                }
            }
            if (H.determinant() < 1e-9) break;  // nothing to align against
            const Eigen::Vector3d dx = -H.ldlt().solve(g);
            Isometry3 D = Isometry3::Identity();
            D.linear() = Eigen::AngleAxisd(dx.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
            D.translation() = Eigen::Vector3d(dx.x(), dx.y(), 0.0);
            T = D * T;
            if (dx.head<2>().norm() < params.convergence_m &&
                std::abs(dx.z()) < params.convergence_m)
                break;
        }
    }
    double sum2 = 0.0;
    std::size_t inliers = 0;
    for (const Eigen::Vector3d& q : points) {
        const Eigen::Vector3d p = T * q;
        const std::optional<odometry::MapMatch> m = reference.nearest(p, params.inlier_m);
        if (!m) continue;
        const double r = m->shape == odometry::VoxelShape::kPlane ? m->axis.dot(p - m->point)
                                                                  : (p - m->point).head<2>().norm();
        sum2 += r * r;
        ++inliers;
    }
    out.T_reference_session = T;
    out.residual_m = inliers ? std::sqrt(sum2 / static_cast<double>(inliers)) : 0.0;
    out.inlier_fraction =
        points.empty() ? 0.0 : static_cast<double>(inliers) / static_cast<double>(points.size());
    const Isometry3 C = T * initial.inverse();
    out.correction_m = C.translation().head<2>().norm();
    out.correction_deg = std::abs(rad_to_deg(std::atan2(C.linear()(1, 0), C.linear()(0, 0))));
    return out;
}

}  // namespace makeway::labelling
