// Session-to-session alignment recovers a known planar offset of a room's map.
#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/labelling/session_align.hpp"

namespace makeway::labelling {
namespace {

std::vector<Eigen::Vector3d> room() {
    std::vector<Eigen::Vector3d> pts;
    for (double z = 0.1; z < 2.0; z += 0.05) {
        for (double t = -5; t <= 5; t += 0.05) {
            pts.emplace_back(t, -3, z);
            pts.emplace_back(t, 3, z);
        }
        for (double t = -3; t <= 3; t += 0.05) {
            pts.emplace_back(-5, t, z);
            pts.emplace_back(5, t, z);
        }
        for (double t = 0; t < 0.4; t += 0.05) {  // a pillar
            pts.emplace_back(1 + t, 1, z);
            pts.emplace_back(1, 1 + t, z);
        }
    }
    return pts;
}

TEST(SessionAlign, RecoversAKnownOffset) {
    odometry::VoxelMap reference;
    reference.add(room());
    Isometry3 T_true = make_T_xyz_yaw(Eigen::Vector3d(0.12, -0.08, 0.0), deg_to_rad(2.0));
    std::vector<Eigen::Vector3d> session;
    for (const Eigen::Vector3d& p : room()) session.push_back(T_true.inverse() * p);
    const SessionAlignment a = align_session(reference, session, {});
    const Isometry3 E = a.T_reference_session * T_true.inverse();
    EXPECT_LT(E.translation().norm(), 0.005);
    EXPECT_LT(std::abs(std::atan2(E.linear()(1, 0), E.linear()(0, 0))), deg_to_rad(0.1));
    EXPECT_LT(a.residual_m, 0.01);
    // The reference map keeps at most 20 points per 25 cm voxel (5 cm wall spacing gives 25): some
    // points have no reference point within 5 cm even when aligned exactly.
    EXPECT_GT(a.inlier_fraction, 0.8);
    EXPECT_NEAR(a.correction_m, std::hypot(0.12, 0.08), 0.005);
    EXPECT_NEAR(a.correction_deg, 2.0, 0.1);
    // Nothing to align against: the initial guess comes back, no inliers.
    const SessionAlignment none = align_session(odometry::VoxelMap{}, session, {});
    EXPECT_TRUE(none.T_reference_session.isApprox(Isometry3::Identity()));
    EXPECT_EQ(none.inlier_fraction, 0.0);
}

}  // namespace
}  // namespace makeway::labelling
