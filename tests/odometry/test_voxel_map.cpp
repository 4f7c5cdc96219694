// The odometry's voxel map against a brute force over its definition (voxel_map.hpp): the nearest
// point among the 27 voxels around a query, each voxel holding the first max_points_per_voxel
// points it was given.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "makeway/common/random.hpp"
#include "makeway/odometry/voxel_map.hpp"

namespace makeway::odometry {
namespace {

TEST(VoxelMap, NearestIsTheBruteForceNearestAmongTheTwentySevenVoxels) {
    VoxelMapParams params;
    params.voxel_m = 0.25;
    params.max_points_per_voxel = 20;
    Rng rng(3);
    // Walls (thin slabs, what a voxel of a wall holds), a blob, and scattered points.
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 3000; ++i)
        points.emplace_back(uniform(rng, -2.0, 2.0), 1.03 + normal(rng, 0.0, 0.005),
                            uniform(rng, 0.0, 1.5));
    for (int i = 0; i < 2000; ++i)
        points.emplace_back(-0.97 + normal(rng, 0.0, 0.005), uniform(rng, -2.0, 2.0),
                            uniform(rng, 0.0, 1.5));
    for (int i = 0; i < 500; ++i)
        points.emplace_back(normal(rng, 0.4, 0.1), normal(rng, -0.3, 0.1), normal(rng, 0.5, 0.1));
    for (int i = 0; i < 500; ++i)
        points.emplace_back(uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0),
                            uniform(rng, 0.0, 1.5));
    VoxelMap map(params);
    map.add(points);

    using Key = std::tuple<int, int, int>;
    auto key = [&](const Eigen::Vector3d& p) {
        return Key{static_cast<int>(std::floor(p.x() / params.voxel_m)),
                   static_cast<int>(std::floor(p.y() / params.voxel_m)),
                   static_cast<int>(std::floor(p.z() / params.voxel_m))};
    };
    std::map<Key, std::vector<Eigen::Vector3d>> kept;
    for (const Eigen::Vector3d& p : points) {
        std::vector<Eigen::Vector3d>& v = kept[key(p)];
        if (static_cast<int>(v.size()) < params.max_points_per_voxel) v.push_back(p);
    }
    int found = 0;
    for (int i = 0; i < 4000; ++i) {
        // Queries near the walls (where a neighbour's box decides), and anywhere.
        const Eigen::Vector3d q =
            i % 2 == 0 ? Eigen::Vector3d(uniform(rng, -2.0, 2.0), 1.03 + normal(rng, 0.0, 0.1),
                                         uniform(rng, 0.0, 1.5))
                       : Eigen::Vector3d(uniform(rng, -2.2, 2.2), uniform(rng, -2.2, 2.2),
                                         uniform(rng, -0.2, 1.7));
        const double max_distance = i % 3 == 0 ? 0.1 : 0.5;
        const auto [kx, ky, kz] = key(q);
        double best = max_distance * max_distance;
        const Eigen::Vector3d* truth = nullptr;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = kept.find({kx + dx, ky + dy, kz + dz});
                    if (it == kept.end()) continue;
                    for (const Eigen::Vector3d& p : it->second) {
                        if ((p - q).squaredNorm() < best) best = (p - q).squaredNorm(), truth = &p;
                    }
                }
        const std::optional<MapMatch> m = map.nearest(q, max_distance);
        ASSERT_EQ(m.has_value(), truth != nullptr) << "query " << i;
        if (!m) continue;
        ++found;
        EXPECT_EQ(m->point, *truth) << "query " << i;
        EXPECT_EQ(m->distance_m, std::sqrt(best)) << "query " << i;
    }
    EXPECT_GT(found, 1000);
}

// A damaged cloud's coordinates beyond int's range of voxels (and float's) share the edge voxel:
// added and found again, nothing undefined on the way.
TEST(VoxelMap, CoordinatesBeyondTheGridShareTheEdgeVoxel) {
    VoxelMap map;
    const Eigen::Vector3d far(1e300, -1e300, 0.1), near(0.1, 0.1, 0.1);
    map.add({far, near});
    EXPECT_EQ(map.num_voxels(), 2u);
    const std::optional<MapMatch> m = map.nearest(far, 1.0);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->point, far);
    EXPECT_EQ(map.nearest(near, 0.05)->point, near);
}

}  // namespace
}  // namespace makeway::odometry
