#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"

namespace makeway {
namespace {

OrientedBox box(double x, double y, double z, double l, double w, double h, double yaw = 0.0) {
    return OrientedBox{{x, y, z}, {l, w, h}, yaw};
}

TEST(BoxOverlap, IdenticalBoxes) {
    const OrientedBox a = box(1, 2, 0.5, 1.2, 0.8, 0.75, 0.3);
    const BoxOverlap o = box_overlap_3d(a, a);
    EXPECT_NEAR(o.iou, 1.0, 1e-12);
    EXPECT_NEAR(o.giou, 1.0, 1e-12);
    EXPECT_NEAR(o.intersection_m3, a.volume_m3(), 1e-12);
}

TEST(BoxOverlap, DisjointBoxesHaveNegativeGiou) {
    // Unit cubes 3 m apart: hull 4 x 1 x 1 = 4, union 2 -> GIoU = -(4 - 2) / 4.
    const BoxOverlap o = box_overlap_3d(box(0, 0, 0, 1, 1, 1), box(3, 0, 0, 1, 1, 1));
    EXPECT_EQ(o.iou, 0.0);
    EXPECT_NEAR(o.giou, -0.5, 1e-12);
}

TEST(BoxOverlap, DisjointInHeightOnly) {
    // Same footprint, stacked with a 1 m gap: hull 1 x 1 x 3.
    const BoxOverlap o = box_overlap_3d(box(0, 0, 0, 1, 1, 1), box(0, 0, 2, 1, 1, 1));
    EXPECT_EQ(o.iou, 0.0);
    EXPECT_NEAR(o.giou, -1.0 / 3.0, 1e-12);
}

TEST(BoxOverlap, RotatedBy45Degrees) {
    // Unit square and itself turned by 45 degrees: the overlap is a regular octagon of area
    // 2(sqrt 2 - 1); the hull is the octagon of the 8 corners, area sqrt 2.
    const double inter = 2.0 * (std::sqrt(2.0) - 1.0);
    const double uni = 2.0 - inter;
    const BoxOverlap o = box_overlap_3d(box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1, kPi / 4));
    EXPECT_NEAR(o.iou, inter / uni, 1e-12);
    EXPECT_NEAR(o.giou, inter / uni - (std::sqrt(2.0) - uni) / std::sqrt(2.0), 1e-12);
}

TEST(BoxOverlap, RotatedBy90Degrees) {
    // A 2 x 1 box and itself turned by 90 degrees: a 1 x 1 overlap, union 3, hull 4 - 4 * 0.125.
    const BoxOverlap o = box_overlap_3d(box(0, 0, 0, 2, 1, 1), box(0, 0, 0, 2, 1, 1, kPi / 2));
    EXPECT_NEAR(o.iou, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(o.giou, 1.0 / 3.0 - 0.5 / 3.5, 1e-12);
    // A square box is unchanged by a quarter turn.
    EXPECT_NEAR(iou_3d(box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1, kPi / 2)), 1.0, 1e-12);
}

TEST(BoxOverlap, ContainedBox) {
    const BoxOverlap o = box_overlap_3d(box(0, 0, 0, 2, 2, 2, 0.4), box(0.1, 0, 0, 1, 1, 1, 1.0));
    EXPECT_NEAR(o.iou, 1.0 / 8.0, 1e-12);
    EXPECT_NEAR(o.giou, o.iou, 1e-12);  // the enclosing volume is the big box itself
}

TEST(BoxOverlap, TouchingBoxes) {
    const BoxOverlap side = box_overlap_3d(box(0, 0, 0, 1, 1, 1), box(1, 0, 0, 1, 1, 1));
    EXPECT_EQ(side.iou, 0.0);
    EXPECT_NEAR(side.giou, 0.0, 1e-12);  // hull == union
    const BoxOverlap corner = box_overlap_3d(box(0, 0, 0, 1, 1, 1), box(1, 1, 0, 1, 1, 1));
    EXPECT_EQ(corner.iou, 0.0);
    EXPECT_NEAR(corner.giou, -(3.0 - 2.0) / 3.0, 1e-12);  // hull: 2x2 minus two corner triangles
}

TEST(BoxOverlap, PartialHeightOverlap) {
    EXPECT_NEAR(iou_3d(box(0, 0, 0, 1, 1, 1), box(0, 0, 0.5, 1, 1, 1)), 0.5 / 1.5, 1e-12);
}

TEST(BoxOverlap, DegenerateBoxesGiveDefinedValues) {
    const OrientedBox flat = box(0, 0, 0, 1, 1, 0);
    const BoxOverlap o = box_overlap_3d(flat, flat);
    EXPECT_EQ(o.iou, 0.0);
    EXPECT_TRUE(std::isfinite(o.giou));
}

TEST(BoxOverlap, SymmetricAndBounded) {
    Rng rng = make_rng(7);
    for (int i = 0; i < 500; ++i) {
        const OrientedBox a =
            box(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, 0, 1), uniform(rng, 0.2, 2),
                uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, -kPi, kPi));
        const OrientedBox b =
            box(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, 0, 1), uniform(rng, 0.2, 2),
                uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, -kPi, kPi));
        const BoxOverlap ab = box_overlap_3d(a, b);
        const BoxOverlap ba = box_overlap_3d(b, a);
        EXPECT_NEAR(ab.iou, ba.iou, 1e-9);
        EXPECT_NEAR(ab.giou, ba.giou, 1e-9);
        EXPECT_GE(ab.iou, 0.0);
        EXPECT_LE(ab.iou, 1.0);
        EXPECT_GE(ab.giou, -1.0);
        EXPECT_LE(ab.giou, ab.iou + 1e-12);
    }
}

// Brute force: the share of uniform samples in the common bounding box that fall in both boxes.
TEST(BoxOverlap, MatchesMonteCarloOnRandomPairs) {
    Rng rng = make_rng(11);
    constexpr int kSamples = 200000;
    for (int pair = 0; pair < 12; ++pair) {
        const OrientedBox a = box(0, 0, 0.5, uniform(rng, 0.5, 2), uniform(rng, 0.5, 2),
                                  uniform(rng, 0.5, 1.5), uniform(rng, -kPi, kPi));
        const OrientedBox b =
            box(uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), uniform(rng, 0.2, 0.8),
                uniform(rng, 0.5, 2), uniform(rng, 0.5, 2), uniform(rng, 0.5, 1.5),
                uniform(rng, -kPi, kPi));
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
        for (const auto& c : a.corners()) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
        for (const auto& c : b.corners()) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
        int in_both = 0, in_either = 0;
        for (int s = 0; s < kSamples; ++s) {
            const Eigen::Vector3d p(uniform(rng, lo.x(), hi.x()), uniform(rng, lo.y(), hi.y()),
                                    uniform(rng, lo.z(), hi.z()));
            const bool ia = a.contains(p), ib = b.contains(p);
            in_both += ia && ib;
            in_either += ia || ib;
        }
        const double mc_iou = static_cast<double>(in_both) / in_either;
        const double sigma = std::sqrt(mc_iou * (1 - mc_iou) / in_either);
        EXPECT_NEAR(iou_3d(a, b), mc_iou, 4 * sigma + 1e-3) << "pair " << pair;
    }
}

TEST(BoxOverlap, BevIou) {
    EXPECT_NEAR(iou_bev(box(0, 0, 0, 2, 1, 1), box(0, 0, 5, 2, 1, 3, kPi / 2)), 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(bev_intersection_area_m2(box(0, 0, 0, 2, 2, 1), box(1, 1, 0, 2, 2, 1)), 1.0, 1e-12);
}

}  // namespace
}  // namespace makeway
