#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway {
namespace {

PointCloud three_points() {
    PointCloud c;
    c.resize(3, PointFields{.intensity = true, .label = true});
    c.xyz = {{0, 0, 0}, {1, 2, 3}, {NAN, 0, 0}};
    c.intensity = {1, 2, 3};
    c.label = {4, 5, 6};
    return c;
}

TEST(PointCloudTest, FieldsFollowChannels) {
    const PointCloud c = three_points();
    EXPECT_EQ(c.fields(), (PointFields{.intensity = true, .label = true}));
    EXPECT_EQ(c.consistency_error(), "");
    PointCloud bad = c;
    bad.ring = {1};
    EXPECT_NE(bad.consistency_error().find("ring"), std::string::npos);
}

TEST(PointCloudTest, NonFiniteCountBoundsAndRemoval) {
    const PointCloud c = three_points();
    EXPECT_EQ(c.count_non_finite(), 1u);
    const PointBounds b = compute_bounds(c);
    ASSERT_TRUE(b.valid);
    EXPECT_EQ(b.max_m, Eigen::Vector3f(1, 2, 3));
    const PointCloud clean = remove_non_finite(c);
    EXPECT_EQ(clean.size(), 2u);
    EXPECT_EQ(clean.label, (std::vector<std::uint8_t>{4, 5}));
    EXPECT_FALSE(compute_bounds(PointCloud{}).valid);
}

TEST(PointCloudTest, SelectAppendTransform) {
    PointCloud c = three_points();
    const PointCloud s = c.select({1});
    EXPECT_EQ(s.size(), 1u);
    EXPECT_EQ(s.intensity[0], 2.0f);
    c.append(s);
    EXPECT_EQ(c.size(), 4u);
    EXPECT_EQ(c.label.back(), 5);
    PointCloud other;
    other.xyz = {{0, 0, 0}};
    EXPECT_THROW(c.append(other), std::invalid_argument);
    const PointCloud t = s.transformed(make_T_xyz_yaw({1, 0, 0}, 3.14159265358979323846));
    EXPECT_NEAR(t.xyz[0].x(), 0.0f, 1e-5);
    EXPECT_NEAR(t.xyz[0].y(), -2.0f, 1e-5);
}

}  // namespace
}  // namespace makeway
