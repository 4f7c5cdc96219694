#include <gtest/gtest.h>

#include "makeway/common/polygon2d.hpp"

namespace makeway {
namespace {

Polygon2 square(double x0, double y0, double side) {
    return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

TEST(Polygon2d, SignedAreaFollowsOrientation) {
    Polygon2 sq = square(0, 0, 2);
    EXPECT_DOUBLE_EQ(signed_area(sq), 4.0);
    std::reverse(sq.begin(), sq.end());
    EXPECT_DOUBLE_EQ(signed_area(sq), -4.0);
    EXPECT_EQ(signed_area({}), 0.0);
}

TEST(Polygon2d, ClipOverlappingSquares) {
    EXPECT_NEAR(signed_area(clip_convex(square(0, 0, 2), square(1, 1, 2))), 1.0, 1e-12);
    EXPECT_NEAR(signed_area(clip_convex(square(0, 0, 1), square(-1, -1, 4))), 1.0, 1e-12);
}

TEST(Polygon2d, ClipDisjointIsEmptyOrZero) {
    EXPECT_NEAR(signed_area(clip_convex(square(0, 0, 1), square(5, 5, 1))), 0.0, 1e-12);
    EXPECT_TRUE(clip_convex({}, square(0, 0, 1)).empty());
}

TEST(Polygon2d, HullDropsInteriorAndCollinearPoints) {
    Polygon2 pts = square(0, 0, 2);
    pts.push_back({1, 1});  // interior
    pts.push_back({1, 0});  // on an edge
    pts.push_back({0, 0});  // duplicate
    const Polygon2 hull = convex_hull(pts);
    EXPECT_EQ(hull.size(), 4u);
    EXPECT_DOUBLE_EQ(signed_area(hull), 4.0);
}

TEST(Polygon2d, HullOfFewPoints) {
    EXPECT_EQ(convex_hull({}).size(), 0u);
    EXPECT_EQ(convex_hull({{1, 1}}).size(), 1u);
}

}  // namespace
}  // namespace makeway
