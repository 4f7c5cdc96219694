// The ray-tracing classification on a constructed two-session scene: a chair present in the first
// session only is Movable, the wall behind it Permanent, a walker seen in two sweeps Dynamic.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "makeway/common/angles.hpp"
#include "makeway/labelling/occupancy.hpp"

namespace makeway::labelling {
namespace {

struct Box3 {
    Eigen::Vector3d lo, hi;
};

// Distance along a unit ray to an axis-aligned box (slab test).
std::optional<double> hit_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box3& b) {
    double t0 = 0.0, t1 = 1e9;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return std::nullopt;
            continue;
        }
        double ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 > t1) return std::nullopt;
    return t0;
}

// One sweep from `origin`: the floor (z = 0), a wall (x = 5.95) and the given boxes. Surfaces lie
// mid-voxel (the grid starts at -1 with 0.1 m voxels), so a return's voxel is not a rounding
// matter.
std::vector<Eigen::Vector3f> sweep(const Eigen::Vector3d& origin, const std::vector<Box3>& boxes) {
    std::vector<Eigen::Vector3f> pts;
    for (double az = -40; az <= 40; az += 0.5) {
        for (double el = -15; el <= 10; el += 1.0) {
            const double a = deg_to_rad(az), e = deg_to_rad(el);
            const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                    std::sin(e));
            double t = (5.95 - origin.x()) / d.x();
            if (d.z() < 0) t = std::min(t, -origin.z() / d.z());
            for (const Box3& b : boxes) {
                if (const auto tb = hit_box(origin, d, b)) t = std::min(t, *tb);
            }
            pts.push_back((origin + t * d).cast<float>());
        }
    }
    return pts;
}

TEST(MultiSessionOccupancy, ClassifiesAMovedChairAWallAndAWalker) {
    const Box3 chair{{2.85, -0.2, 0.0}, {3.25, 0.2, 0.9}};
    const Box3 walker{{4.05, 0.8, 0.0}, {4.35, 1.1, 1.7}};
    MultiSessionOccupancy occ(
        {}, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -6, -0.5), Eigen::Vector3d(7, 6, 3)), 2);
    for (int s = 0; s < 2; ++s) {
        for (int k = 0; k < 10; ++k) {
            const Eigen::Vector3d origin(0.2 * k, -0.5, 0.8);
            std::vector<Box3> boxes;
            if (s == 0) boxes.push_back(chair);            // moved away before session 2
            if (s == 0 && k < 2) boxes.push_back(walker);  // walks out of view after two sweeps
            occ.add_sweep(s, origin, sweep(origin, boxes));
        }
    }
    const Eigen::Vector3d chair_front(2.86, 0.0, 0.5), wall(5.96, 0.0, 1.0),
        walker_front(4.06, 0.95, 1.0);
    EXPECT_GE(occ.evidence(0, chair_front).hits, 5);
    EXPECT_GE(occ.evidence(1, chair_front).free, 5);
    EXPECT_EQ(occ.evidence(1, chair_front).hits, 0);
    EXPECT_EQ(occ.classify(0, chair_front), PointClass::kMovable);
    EXPECT_EQ(occ.classify(0, wall), PointClass::kPermanent);
    EXPECT_EQ(occ.classify(1, wall), PointClass::kPermanent);
    EXPECT_EQ(occ.evidence(0, walker_front).hits, 2);
    EXPECT_EQ(occ.classify(0, walker_front), PointClass::kDynamic);
    // Where the chair stood, a point of the second session would be free space: it never saw one
    // there, and nothing has evidence outside the grid.
    EXPECT_EQ(occ.classify(0, Eigen::Vector3d(100, 0, 0)), PointClass::kPermanent);
}

TEST(MultiSessionOccupancy, CountsSweepsNotRaysAndStopsShortOfTheReturn) {
    OccupancyParams p;
    p.voxel_m = 0.1;
    MultiSessionOccupancy occ(
        p, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 1)), 1);
    // Two rays of one sweep along x through the same voxels, ending 0.9 m out.
    occ.add_sweep(0, Eigen::Vector3d(0.05, 0.05, 0.05),
                  {Eigen::Vector3f(0.95f, 0.05f, 0.05f), Eigen::Vector3f(0.95f, 0.06f, 0.05f)});
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.55, 0.05, 0.05)).free, 1);
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.95, 0.05, 0.05)).hits, 1);
    // Free space ends 0.15 m + 2 % of the range short of the return (at x = 0.78): the voxel it
    // ends in is free, the one before the return's is not.
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.85, 0.05, 0.05)).free, 0);
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.75, 0.05, 0.05)).free, 1);
    // A second sweep counts again.
    occ.add_sweep(0, Eigen::Vector3d(0.05, 0.05, 0.05), {Eigen::Vector3f(0.95f, 0.05f, 0.05f)});
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.55, 0.05, 0.05)).free, 2);
    EXPECT_EQ(occ.evidence(0, Eigen::Vector3d(0.95, 0.05, 0.05)).hits, 2);
    // A grid too large for max_voxels is refused with a clear message.
    p.max_voxels = 1000;
    EXPECT_THROW(
        MultiSessionOccupancy(
            p, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d(10, 10, 3)), 2),
        std::invalid_argument);
}

}  // namespace
}  // namespace makeway::labelling
