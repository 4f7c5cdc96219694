#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/common/oriented_box.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway {
namespace {

TEST(Angles, WrapIntoHalfOpenRange) {
    EXPECT_NEAR(wrap_angle(0.0), 0.0, 1e-15);
    EXPECT_NEAR(wrap_angle(kPi), -kPi, 1e-12);
    EXPECT_NEAR(wrap_angle(-kPi), -kPi, 1e-12);
    EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-12);
    EXPECT_NEAR(wrap_angle(-7.0 * kPi / 2), kPi / 2, 1e-12);
    EXPECT_NEAR(angle_diff(deg_to_rad(179), deg_to_rad(-179)), deg_to_rad(-2), 1e-12);
    EXPECT_NEAR(rad_to_deg(deg_to_rad(33.0)), 33.0, 1e-12);
}

TEST(Transforms, Pose2RoundTrip) {
    const Pose2 p{1.5, -2.0, 2.5};
    const Pose2 q = to_pose2(to_isometry(p));
    EXPECT_NEAR(q.x_m, p.x_m, 1e-12);
    EXPECT_NEAR(q.y_m, p.y_m, 1e-12);
    EXPECT_NEAR(q.yaw_rad, p.yaw_rad, 1e-12);
    const Pose2 r = project_to_plane(lift_to_3d(p, 0.4));
    EXPECT_NEAR(r.yaw_rad, p.yaw_rad, 1e-12);
}

TEST(Transforms, ComposeFollowsFrameNames) {
    const Isometry3 T_world_robot = make_T_xyz_yaw({1, 0, 0}, kPi / 2);
    const Isometry3 T_robot_sensor = make_T_xyz_yaw({0.5, 0, 0.4}, 0.0);
    const Isometry3 T_world_sensor = T_world_robot * T_robot_sensor;
    EXPECT_TRUE(T_world_sensor.translation().isApprox(Eigen::Vector3d(1, 0.5, 0.4), 1e-12));
    EXPECT_NEAR(yaw_of(T_world_sensor), kPi / 2, 1e-12);
}

TEST(Transforms, InterpolateEndpointsAndMiddle) {
    const Isometry3 a = make_T_xyz_yaw({0, 0, 0}, 0.0);
    const Isometry3 b = make_T_xyz_yaw({2, 0, 0}, 1.0);
    EXPECT_TRUE(interpolate(a, b, 0.0).isApprox(a, 1e-12));
    EXPECT_TRUE(interpolate(a, b, 1.0).isApprox(b, 1e-12));
    const Isometry3 mid = interpolate(a, b, 0.5);
    EXPECT_NEAR(yaw_of(mid), 0.5, 1e-12);
    EXPECT_NEAR(mid.translation().x(), 1.0, 1e-12);
}

TEST(OrientedBoxTest, CornersAndContainment) {
    const OrientedBox b{{1, 1, 0.5}, {2, 1, 1}, kPi / 2};
    const auto bev = b.bev_corners();
    EXPECT_TRUE(bev[0].isApprox(Eigen::Vector2d(1.5, 0), 1e-12));  // (-l/2, -w/2) turned 90 deg
    EXPECT_TRUE(b.contains({1.4, 1.9, 0.9}));
    EXPECT_FALSE(b.contains({1.9, 1.0, 0.5}));
    EXPECT_TRUE(b.contains({1.9, 1.0, 0.5}, 0.5));
    EXPECT_NEAR(b.volume_m3(), 2.0, 1e-12);
}

TEST(OrientedBoxTest, TransformMatchesTransformedCorners) {
    const OrientedBox b{{1, 2, 0.4}, {1.2, 0.6, 0.8}, 0.7};
    const Isometry3 T = make_T_xyz_yaw({-3, 1, 0.2}, -2.0);
    const OrientedBox t = b.transformed(T);
    const auto c_b = b.corners();
    const auto c_t = t.corners();
    for (int i = 0; i < 8; ++i) EXPECT_TRUE((T * c_b[i]).isApprox(c_t[i], 1e-9)) << i;
}

TEST(OrientedBoxTest, Validity) {
    EXPECT_TRUE((OrientedBox{{0, 0, 0}, {1, 1, 1}, 0}).is_valid());
    EXPECT_FALSE((OrientedBox{{0, 0, 0}, {1, 0, 1}, 0}).is_valid());
    EXPECT_FALSE((OrientedBox{{NAN, 0, 0}, {1, 1, 1}, 0}).is_valid());
}

}  // namespace
}  // namespace makeway
