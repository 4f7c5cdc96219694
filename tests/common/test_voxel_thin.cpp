#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "makeway/common/random.hpp"
#include "makeway/common/voxel_thin.hpp"

namespace makeway {
namespace {

// Brute force: the first finite point of each voxel (std::floor of each axis), in input order.
std::vector<Eigen::Vector3d> reference_thin(const std::vector<Eigen::Vector3d>& points,
                                            double voxel) {
    std::set<std::tuple<double, double, double>> seen;
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : points) {
        if (!p.allFinite()) continue;
        const auto key = std::make_tuple(std::floor(p.x() / voxel), std::floor(p.y() / voxel),
                                         std::floor(p.z() / voxel));
        if (seen.insert(key).second) out.push_back(p);
    }
    return out;
}

TEST(VoxelThin, KeepsTheFirstPointOfEveryVoxelAsTheBruteForceDoes) {
    Rng rng = make_rng(11);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 5000; ++i)  // both signs, voxel edges on the axes included
        points.emplace_back(uniform(rng, -3.0, 3.0), uniform(rng, -3.0, 3.0),
                            std::round(uniform(rng, -2.0, 2.0) * 4.0) / 4.0);
    points.emplace_back(NAN, 0.0, 0.0);
    const auto thin = voxel_thin(points, 0.25);
    const auto want = reference_thin(points, 0.25);
    ASSERT_EQ(thin.size(), want.size());
    for (std::size_t i = 0; i < thin.size(); ++i) EXPECT_EQ(thin[i], want[i]) << i;
    EXPECT_LT(thin.size(), 5000u);
}

// A finite point may lie up to 3e38 m away (a damaged or hostile cloud): its key must not
// overflow (UBSan stopped `detect` on one), and the points near the sensor are thinned as ever.
TEST(VoxelThin, PointsAsFarAsFloatsGoLeaveTheNearOnesAlone) {
    const double far = std::numeric_limits<float>::max();
    const std::vector<Eigen::Vector3d> points{
        {far, -far, 0.0}, {0.11, 0.11, 0.11}, {-far, far, -far}, {0.12, 0.11, 0.11}, {0.31, 0, 0}};
    const auto thin = voxel_thin(points, 0.1);
    ASSERT_GE(thin.size(), 3u);
    EXPECT_EQ(thin.front(), points[0]);
    EXPECT_EQ(thin.back(), points[4]);
    EXPECT_EQ(std::count(thin.begin(), thin.end(), points[1]), 1);
    EXPECT_EQ(std::count(thin.begin(), thin.end(), points[3]), 0);  // (0.11's voxel)
}

}  // namespace
}  // namespace makeway
