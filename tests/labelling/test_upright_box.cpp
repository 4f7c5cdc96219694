// PCA boxes of constructed clusters: known centre, size and yaw.
#include <gtest/gtest.h>

#include <random>

#include "makeway/common/angles.hpp"
#include "makeway/labelling/upright_box.hpp"

namespace makeway::labelling {
namespace {

// Points on the surface of a box (what a LiDAR map of a piece of furniture roughly is).
std::vector<Eigen::Vector3d> box_surface(const OrientedBox& box, int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    std::uniform_int_distribution<int> face(0, 5);
    std::vector<Eigen::Vector3d> pts;
    const Isometry3 T = box.T_frame_box();
    for (int k = 0; k < n; ++k) {
        Eigen::Vector3d q(u(rng), u(rng), u(rng));
        const int f = face(rng);
        q[f / 2] = f % 2 ? 0.5 : -0.5;
        pts.push_back(T * q.cwiseProduct(box.size_m));
    }
    return pts;
}

double yaw_error_mod_pi(double a, double b) {
    const double e = std::abs(wrap_angle(a - b));
    return std::min(e, kPi - e);
}

TEST(UprightPcaBox, RecoversConstructedBoxes) {
    for (int k = 0; k < 12; ++k) {
        OrientedBox truth;
        truth.size_m =
            Eigen::Vector3d(1.2 + 0.05 * k, 0.6, 0.75);  // elongated: the yaw is defined mod pi
        truth.yaw_rad = wrap_angle(-3.0 + 0.5 * k);
        truth.centre_m = Eigen::Vector3d(0.3 * k - 2.0, 1.0 - 0.2 * k, 0.375);
        const OrientedBox got =
            upright_pca_box(box_surface(truth, 3000, static_cast<std::uint32_t>(k)));
        EXPECT_LT(rad_to_deg(yaw_error_mod_pi(got.yaw_rad, truth.yaw_rad)), 2.0) << k;
        EXPECT_GT(got.yaw_rad, -kPi / 2 - 1e-9);
        EXPECT_LE(got.yaw_rad, kPi / 2 + 1e-9);
        EXPECT_LT((got.centre_m - truth.centre_m).norm(), 0.03) << k;
        EXPECT_NEAR(got.size_m.x(), truth.size_m.x(), 0.04) << k;
        EXPECT_NEAR(got.size_m.y(), truth.size_m.y(), 0.04) << k;
        EXPECT_NEAR(got.size_m.z(), truth.size_m.z(), 1e-9) << k;
    }
}

TEST(UprightPcaBox, ExtendsToTheFloorAndHandlesDegenerateClusters) {
    // A table top seen alone (0.7-0.75 m) stands on the floor at z = 0.
    OrientedBox top;
    top.size_m = Eigen::Vector3d(1.0, 0.5, 0.05);
    top.centre_m = Eigen::Vector3d(1, 1, 0.725);
    const OrientedBox got = upright_pca_box(box_surface(top, 2000, 1), 0.0);
    EXPECT_NEAR(got.z_min_m(), 0.0, 1e-9);
    EXPECT_NEAR(got.z_max_m(), 0.75, 1e-9);
    // A floor below the points' lowest never shrinks the box; one above it is ignored.
    EXPECT_NEAR(upright_pca_box(box_surface(top, 2000, 1), 0.72).z_min_m(), 0.70, 1e-9);
    // Empty: a zero box; a vertical line: yaw 0, zero footprint.
    EXPECT_EQ(upright_pca_box({}).size_m, Eigen::Vector3d::Zero());
    const OrientedBox line = upright_pca_box({Eigen::Vector3d(1, 2, 0), Eigen::Vector3d(1, 2, 1)});
    EXPECT_EQ(line.yaw_rad, 0.0);
    EXPECT_NEAR(line.size_m.z(), 1.0, 1e-12);
    EXPECT_NEAR(line.size_m.x(), 0.0, 1e-12);
}

}  // namespace
}  // namespace makeway::labelling
