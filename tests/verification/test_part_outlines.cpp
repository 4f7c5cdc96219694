#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "makeway/sim/furniture.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/part_outlines.hpp"

namespace makeway::verification {
namespace {

// The finest level's points of one procedural model, as the pipeline reads them.
std::vector<Eigen::Vector3d> model_points(sim::FurnitureStyle style, std::uint32_t seed) {
    CadLibrary library;
    library.add("m", ObjectClass::kTable, sim::make_furniture(style, seed).mesh_object);
    return library.models().front().levels.back().points_object;
}

bool inside_any(const std::vector<Polygon2>& outlines, const Eigen::Vector2d& p, double tol_m) {
    return std::any_of(outlines.begin(), outlines.end(),
                       [&](const Polygon2& o) { return convex_distance(o, p) <= tol_m; });
}

// Brute-force reference: every model point in the body's band lies in an outline.
void expect_covers_the_band(const std::vector<Polygon2>& outlines,
                            const std::vector<Eigen::Vector3d>& points, const BodyHeights& body) {
    for (const Eigen::Vector3d& p : points) {
        if (body.can_hit(p.z())) {
            EXPECT_TRUE(inside_any(outlines, p.head<2>(), 1e-9));
        }
    }
}

TEST(PartOutlines, ARectangularTableGivesFourLegsAndLeavesTheSpaceUnderItsTopOpen) {
    const BodyHeights body;  // 0.02 - 0.5 m: the legs, not the top
    const auto points = model_points(sim::FurnitureStyle::kRectTable, 3);
    const auto outlines = part_outlines(points, body);
    ASSERT_EQ(outlines.size(), 4u);
    expect_covers_the_band(outlines, points, body);
    // Under the middle of the top: free for the robot.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    EXPECT_FALSE(inside_any(outlines, 0.5 * (lo + hi).head<2>(), 0.1));
    for (const Polygon2& leg : outlines) EXPECT_LT(signed_area(leg), 0.1 * 0.1);
}

TEST(PartOutlines, APedestalTableGivesItsFootNotItsTop) {
    const BodyHeights body;
    const auto points = model_points(sim::FurnitureStyle::kRoundTable, 5);
    const auto outlines = part_outlines(points, body);
    ASSERT_EQ(outlines.size(), 1u);  // the foot and the column: one part
    expect_covers_the_band(outlines, points, body);
    // The foot's reach (the band's farthest point from the column) against the top's.
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& q : outlines[0]) centre += q / static_cast<double>(outlines[0].size());
    double foot = 0.0, top = 0.0;
    for (const auto& p : points) {
        double& reach = body.can_hit(p.z()) ? foot : top;
        reach = std::max(reach, (p.head<2>() - centre).norm());
    }
    ASSERT_GT(top, foot + 0.1);  // the model: a top wider than its foot
    for (const auto& q : outlines[0]) EXPECT_LE((q - centre).norm(), foot + 1e-9);
    // A higher clearance rolls over the foot: only the column is left.
    const auto column = part_outlines(points, BodyHeights{0.06, 0.5});
    ASSERT_EQ(column.size(), 1u);
    EXPECT_LT(std::abs(signed_area(column[0])), 0.25 * std::abs(signed_area(outlines[0])));
}

TEST(PartOutlines, NothingInTheBandGivesNoOutlineAndBadInputNoCrash) {
    EXPECT_TRUE(part_outlines({{0.0, 0.0, 0.8}, {0.1, 0.0, 0.9}}, BodyHeights{}).empty());
    EXPECT_TRUE(part_outlines({}, BodyHeights{}).empty());
    EXPECT_TRUE(part_outlines({{0.0, 0.0, 0.1}}, BodyHeights{}, 0.0).empty());
    // One point in the band: its cell's square.
    const auto post = part_outlines({{0.01, 0.01, 0.1}, {NAN, 0.0, 0.1}}, BodyHeights{}, 0.04);
    ASSERT_EQ(post.size(), 1u);
    EXPECT_NEAR(std::abs(signed_area(post[0])), 0.04 * 0.04, 1e-12);
}

}  // namespace
}  // namespace makeway::verification
