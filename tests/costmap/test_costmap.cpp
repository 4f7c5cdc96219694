#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/costmap/affordance_layer.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/layered_costmap.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/costmap/static_layer.hpp"

namespace makeway::costmap {
namespace {

Costmap grid(int n = 100) { return Costmap({0, 0}, 0.05, n, n); }

ObjectEstimate object(ObjectClass cls, Eigen::Vector2d c, double l, double w, double yaw) {
    ObjectEstimate o;
    o.cls = cls;
    o.box_world = {{c.x(), c.y(), 0.4}, {l, w, 0.8}, yaw};
    return o;
}

TEST(Inflation, Nav2FormulaValues) {
    const InflationParams p;  // inscribed 0.215, radius 0.55, k 3
    EXPECT_EQ(inflation_cost(0.0, p), cost::kLethal);
    EXPECT_EQ(inflation_cost(0.1, p), cost::kInscribed);
    EXPECT_EQ(inflation_cost(0.215, p), cost::kInscribed);
    EXPECT_EQ(inflation_cost(0.315, p), 186);  // floor(252 exp(-0.3))
    EXPECT_EQ(inflation_cost(0.55, p), 92);    // floor(252 exp(-1.005))
    EXPECT_EQ(inflation_cost(0.56, p), cost::kFree);
}

TEST(Inflation, HandComputedCellsAroundOneObstacle) {
    LayeredCostmap lc(grid());
    Costmap walls = grid();
    walls.at(50, 50) = cost::kLethal;
    lc.add_layer(std::make_unique<StaticLayer>(walls));
    lc.add_layer(std::make_unique<InflationLayer>(InflationParams{}));
    lc.update({});
    const Costmap& m = lc.master();
    EXPECT_EQ(m.at(50, 50), cost::kLethal);
    EXPECT_EQ(m.at(54, 50), cost::kInscribed);                 // 0.20 m
    EXPECT_EQ(m.at(55, 50), inflation_cost(0.25, {}));         // 0.25 m
    EXPECT_EQ(m.at(53, 54), inflation_cost(0.25, {}));         // 3-4-5 triangle: 0.25 m
    EXPECT_EQ(m.at(50, 61), inflation_cost(0.55, {}));
    EXPECT_EQ(m.at(50, 62), cost::kFree);
}

TEST(Inflation, DistanceTransformMatchesBruteForce) {
    Costmap m = grid(40);
    Rng rng = make_rng(3);
    std::vector<Eigen::Vector2i> lethal;
    for (int i = 0; i < 12; ++i) {
        const Eigen::Vector2i c(static_cast<int>(uniform_int(rng, 0, 39)), static_cast<int>(uniform_int(rng, 0, 39)));
        m.at(c.x(), c.y()) = cost::kLethal;
        lethal.push_back(c);
    }
    const GridWindow all{0, 0, 40, 40};
    const auto d2 = squared_distance_to_lethal(m, all, all);
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 40; ++x) {
            double best = 1e30;
            for (const auto& c : lethal) best = std::min(best, double((c.x() - x) * (c.x() - x) + (c.y() - y) * (c.y() - y)));
            ASSERT_EQ(d2[y * 40 + x], best) << x << " " << y;
        }
    }
}

TEST(Affordance, ChairZoneIsAnEllipseAlongTheChairAxis) {
    const AffordanceParams p;
    for (double yaw : {0.0, 0.7, kPi / 2}) {
        const ObjectEstimate chair = object(ObjectClass::kChair, {2, 2}, 0.5, 0.5, yaw);
        const Eigen::Vector2d fwd(std::cos(yaw), std::sin(yaw)), side(-fwd.y(), fwd.x());
        EXPECT_TRUE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.8 * fwd));   // pulled-out path
        EXPECT_TRUE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) - 0.8 * fwd));
        EXPECT_FALSE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.8 * side));  // narrow sideways
        EXPECT_FALSE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.9 * fwd));
        EXPECT_EQ(zone_cost(chair, p, {2, 2}), 220);  // peak on the chair
        EXPECT_LT(zone_cost(chair, p, Eigen::Vector2d(2, 2) + 0.8 * fwd), zone_cost(chair, p, Eigen::Vector2d(2, 2) + 0.4 * fwd));
    }
}

TEST(Affordance, TableIsPaddedOnItsSittingSidesOnly) {
    const AffordanceParams p;
    const ObjectEstimate table = object(ObjectClass::kTable, {0, 0}, 1.6, 0.8, kPi / 2);  // long axis along world y
    EXPECT_TRUE(in_affordance_zone(table, p, {0.4 + 0.7, 0.0}));    // 0.7 m beside a long side
    EXPECT_FALSE(in_affordance_zone(table, p, {0.4 + 0.8, 0.0}));
    EXPECT_TRUE(in_affordance_zone(table, p, {0.0, 0.8 + 0.1}));    // 0.1 m beyond an end
    EXPECT_FALSE(in_affordance_zone(table, p, {0.0, 0.8 + 0.3}));   // ends are not sat at
    const ObjectEstimate round = object(ObjectClass::kTable, {0, 0}, 1.0, 1.0, 0.3);
    const Eigen::Vector2d x(std::cos(0.3), std::sin(0.3));
    EXPECT_TRUE(in_affordance_zone(round, p, 1.2 * x));  // square tables: sat at all round
    for (double d = 0.0; d < 2.0; d += 0.05) EXPECT_LE(zone_cost(table, p, {d, 0.0}), cost::kMaxSoft);
}

TEST(AffordanceLayer, MovedObjectLeavesNoStaleCost) {
    LayeredCostmap lc(grid());
    lc.add_layer(std::make_unique<AffordanceLayer>(AffordanceParams{}));
    LayerInput in;
    in.objects = {object(ObjectClass::kChair, {1.0, 1.0}, 0.5, 0.5, 0.0)};
    lc.update(in);
    EXPECT_GT(lc.master().at(20, 20), 0);
    in.objects = {object(ObjectClass::kChair, {4.0, 4.0}, 0.5, 0.5, 0.0)};
    lc.update(in);
    for (int y = 0; y < 50; ++y) {
        for (int x = 0; x < 50; ++x) ASSERT_EQ(lc.master().at(x, y), 0) << x << " " << y;
    }
    EXPECT_GT(lc.master().at(80, 80), 0);
    in.objects.clear();
    lc.update(in);
    EXPECT_EQ(lc.master().at(80, 80), 0);
}

TEST(ObstacleLayer, MarksReturnsAndClearsAlongRays) {
    LayeredCostmap lc(grid());
    lc.add_layer(std::make_unique<ObstacleLayer>(grid(), ObstacleLayerParams{}));
    PointCloud pts;
    pts.xyz = {{3.0f, 2.5f, 0.3f}, {3.0f, 2.5f, 0.02f} /* floor: no mark */, {1.0f, 1.0f, 2.0f} /* high */};
    LayerInput in;
    in.points_world = &pts;
    in.sensor_world_m = {0.5, 2.5, 0.45};
    lc.update(in);
    EXPECT_EQ(*lc.master().cost_at({3.0, 2.5}), cost::kLethal);
    EXPECT_EQ(*lc.master().cost_at({1.0, 1.0}), cost::kFree);
    // The obstacle moved away: a ray to the wall behind passes through its cell and clears it.
    pts.xyz = {{4.5f, 2.5f, 0.3f}};
    lc.update(in);
    EXPECT_EQ(*lc.master().cost_at({3.0, 2.5}), cost::kFree);
    EXPECT_EQ(*lc.master().cost_at({4.5, 2.5}), cost::kLethal);
}

}  // namespace
}  // namespace makeway::costmap
