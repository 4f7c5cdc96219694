#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/costmap/affordance_layer.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/layered_costmap.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/costmap/ray_walk.hpp"
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
    EXPECT_EQ(m.at(54, 50), cost::kInscribed);          // 0.20 m
    EXPECT_EQ(m.at(55, 50), inflation_cost(0.25, {}));  // 0.25 m
    EXPECT_EQ(m.at(53, 54), inflation_cost(0.25, {}));  // 3-4-5 triangle: 0.25 m
    EXPECT_EQ(m.at(50, 61), inflation_cost(0.55, {}));
    EXPECT_EQ(m.at(50, 62), cost::kFree);
}

TEST(Inflation, DistanceTransformMatchesBruteForce) {
    Costmap m = grid(40);
    Rng rng = make_rng(3);
    std::vector<Eigen::Vector2i> lethal;
    for (int i = 0; i < 12; ++i) {
        const Eigen::Vector2i c(static_cast<int>(uniform_int(rng, 0, 39)),
                                static_cast<int>(uniform_int(rng, 0, 39)));
        m.at(c.x(), c.y()) = cost::kLethal;
        lethal.push_back(c);
    }
    const GridWindow all{0, 0, 40, 40};
    const auto d2 = squared_distance_to_lethal(m, all, all);
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 40; ++x) {
            double best = 1e30;
            for (const auto& c : lethal)
                best =
                    std::min(best, double((c.x() - x) * (c.x() - x) + (c.y() - y) * (c.y() - y)));
            ASSERT_EQ(d2[y * 40 + x], best) << x << " " << y;
        }
    }
}

// The layer reads its costs from a table by squared distance (issue 31): at every cell the same
// cost as nav2's formula at the brute-force distance, for radii that end on a cell (0.55 m at
// 5 cm: 11 cells) and between cells, and at two resolutions.
TEST(Inflation, TabledCostsEqualTheFormulaAtEveryCell) {
    Rng rng = make_rng(5);
    for (const double resolution : {0.05, 0.1}) {
        for (const InflationParams p :
             {InflationParams{}, InflationParams{0.2, 0.73, 2.0}, InflationParams{0.3, 0.3, 5.0}}) {
            Costmap walls({0, 0}, resolution, 60, 60);
            std::vector<Eigen::Vector2i> lethal;
            for (int i = 0; i < 8; ++i) {
                lethal.emplace_back(static_cast<int>(uniform_int(rng, 0, 59)),
                                    static_cast<int>(uniform_int(rng, 0, 59)));
                walls.at(lethal.back().x(), lethal.back().y()) = cost::kLethal;
            }
            LayeredCostmap lc(Costmap({0, 0}, resolution, 60, 60));
            lc.add_layer(std::make_unique<StaticLayer>(walls));
            lc.add_layer(std::make_unique<InflationLayer>(p));
            lc.update({});
            for (int y = 0; y < 60; ++y) {
                for (int x = 0; x < 60; ++x) {
                    int best = 1 << 30;
                    for (const auto& c : lethal)
                        best =
                            std::min(best, (c.x() - x) * (c.x() - x) + (c.y() - y) * (c.y() - y));
                    ASSERT_EQ(lc.master().at(x, y),
                              inflation_cost(std::sqrt(static_cast<double>(best)) * resolution, p))
                        << x << " " << y << " resolution " << resolution << " radius "
                        << p.inflation_radius_m;
                }
            }
        }
    }
}

TEST(Affordance, ChairZoneIsAnEllipseAlongTheChairAxis) {
    const AffordanceParams p;
    for (double yaw : {0.0, 0.7, kPi / 2}) {
        const ObjectEstimate chair = object(ObjectClass::kChair, {2, 2}, 0.5, 0.5, yaw);
        const Eigen::Vector2d fwd(std::cos(yaw), std::sin(yaw)), side(-fwd.y(), fwd.x());
        EXPECT_TRUE(
            in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.8 * fwd));  // pulled-out path
        EXPECT_TRUE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) - 0.8 * fwd));
        EXPECT_FALSE(
            in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.8 * side));  // narrow sideways
        EXPECT_FALSE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.9 * fwd));
        EXPECT_EQ(zone_cost(chair, p, {2, 2}), 220);  // peak on the chair
        EXPECT_LT(zone_cost(chair, p, Eigen::Vector2d(2, 2) + 0.8 * fwd),
                  zone_cost(chair, p, Eigen::Vector2d(2, 2) + 0.4 * fwd));
    }
}

TEST(Affordance, TableIsPaddedOnItsSittingSidesOnly) {
    const AffordanceParams p;
    const ObjectEstimate table =
        object(ObjectClass::kTable, {0, 0}, 1.6, 0.8, kPi / 2);   // long axis along world y
    EXPECT_TRUE(in_affordance_zone(table, p, {0.4 + 0.7, 0.0}));  // 0.7 m beside a long side
    EXPECT_FALSE(in_affordance_zone(table, p, {0.4 + 0.8, 0.0}));
    EXPECT_TRUE(in_affordance_zone(table, p, {0.0, 0.8 + 0.1}));   // 0.1 m beyond an end
    EXPECT_FALSE(in_affordance_zone(table, p, {0.0, 0.8 + 0.3}));  // ends are not sat at
    const ObjectEstimate round = object(ObjectClass::kTable, {0, 0}, 1.0, 1.0, 0.3);
    const Eigen::Vector2d x(std::cos(0.3), std::sin(0.3));
    EXPECT_TRUE(in_affordance_zone(round, p, 1.2 * x));  // square tables: sat at all round
    for (double d = 0.0; d < 2.0; d += 0.05)
        EXPECT_LE(zone_cost(table, p, {d, 0.0}), cost::kMaxSoft);
}

// The margin (margin_m > 0; 0.15 m by default) lies outside the zone: the risk zone is where it
// was, the cost there falls linearly from margin_cost at the boundary to 1, and nothing past
// margin_m.
TEST(Affordance, MarginFallsOffOutsideTheZoneOnly) {
    AffordanceParams p;
    p.margin_m = 0.15;
    p.margin_cost = 20;
    AffordanceParams none;
    none.margin_m = 0.0;
    // Long axis along x: the zone is x in [-0.95, 0.95] (ends), y in [-1.15, 1.15] (sides).
    const ObjectEstimate table = object(ObjectClass::kTable, {0, 0}, 1.6, 0.8, 0.0);
    EXPECT_EQ(zone_cost(table, p, {0.0, 1.15 + 0.05}), 13);         // 20 (1 - 0.05 / 0.15) = 13.3
    EXPECT_EQ(zone_cost(table, p, {0.95 + 0.06, 1.15 + 0.08}), 7);  // 0.1 m from the corner
    EXPECT_EQ(zone_cost(table, p, {0.95 + 0.14, 0.0}), 1);
    EXPECT_EQ(zone_cost(table, p, {0.95 + 0.16, 0.0}), cost::kFree);
    EXPECT_EQ(zone_cost(table, none, {0.0, 1.15 + 0.05}), cost::kFree);
    EXPECT_FALSE(in_affordance_zone(table, p, {0.0, 1.15 + 0.05}));
    for (double y = 0.0; y <= 1.15; y += 0.05)  // inside: the zone's own costs
        EXPECT_EQ(zone_cost(table, p, {0.3, y}), zone_cost(table, none, {0.3, y}));
    // A chair's ellipse (semi-axes 0.85 along its axis, 0.4 across): distances along the axes.
    const ObjectEstimate chair = object(ObjectClass::kChair, {2, 2}, 0.5, 0.5, 0.7);
    const Eigen::Vector2d fwd(std::cos(0.7), std::sin(0.7)), side(-fwd.y(), fwd.x());
    EXPECT_EQ(zone_cost(chair, p, Eigen::Vector2d(2, 2) + 0.925 * fwd), 10);  // 0.075 m out
    EXPECT_EQ(zone_cost(chair, p, Eigen::Vector2d(2, 2) - 0.43 * side), 16);  // 0.03 m out
    EXPECT_FALSE(in_affordance_zone(chair, p, Eigen::Vector2d(2, 2) + 0.925 * fwd));
    EXPECT_EQ(zone_cost(chair, p, Eigen::Vector2d(2, 2) + 1.01 * fwd), cost::kFree);
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

// The layer keeps each zone's costs from when it was first written and copies them from then on
// (affordance_layer.hpp). After every update of a drifting scene (a table standing, chairs that
// appear, move, come back where they were, vanish and stand inside each other's zones) the master
// equals every zone computed again, cell by cell; with a margin too (its cells are the zone's:
// written, kept and cleared with it).
TEST(AffordanceLayer, ZonesKeptBetweenUpdatesEqualZonesComputedAgain) {
    for (const double margin_m : {0.0, 0.2}) {
        AffordanceParams p;
        p.margin_m = margin_m;
        LayeredCostmap lc(grid());
        lc.add_layer(std::make_unique<AffordanceLayer>(p));
        Rng rng(7);
        const ObjectEstimate table = object(ObjectClass::kTable, {2.5, 2.5}, 1.2, 0.7, 0.4);
        std::vector<ObjectEstimate> chairs = {
            object(ObjectClass::kChair, {1.6, 2.0}, 0.5, 0.5, 0.2),
            object(ObjectClass::kChair, {3.3, 3.1}, 0.45, 0.5, 2.0),
            object(ObjectClass::kChair, {2.4, 1.5}, 0.5, 0.45, -1.2)};
        const std::vector<ObjectEstimate> first = chairs;
        for (int step = 0; step < 40; ++step) {
            LayerInput in;
            in.objects = {table};
            for (std::size_t i = 0; i < chairs.size(); ++i) {
                ObjectEstimate& c = chairs[i];
                const double u = uniform(rng, 0.0, 1.0);
                if (u < 0.3) {  // pulled a little
                    c.box_world.centre_m.x() += uniform(rng, -0.2, 0.2);
                    c.box_world.centre_m.y() += uniform(rng, -0.2, 0.2);
                    c.box_world.yaw_rad += uniform(rng, -0.5, 0.5);
                } else if (u < 0.4) {
                    c = first[i];  // back where it stood
                }
                if (uniform(rng, 0.0, 1.0) < 0.85) in.objects.push_back(c);  // sometimes unseen
            }
            lc.update(in);
            for (int y = 0; y < 100; ++y) {
                for (int x = 0; x < 100; ++x) {
                    std::uint8_t expected = cost::kFree;
                    for (const ObjectEstimate& o : in.objects)
                        expected = std::max(expected, zone_cost(o, p, lc.master().centre_of(x, y)));
                    ASSERT_EQ(lc.master().at(x, y), expected)
                        << "margin " << margin_m << " step " << step << " cell " << x << " " << y;
                }
            }
        }
    }
}

TEST(ObstacleLayer, MarksReturnsAndClearsAlongRays) {
    LayeredCostmap lc(grid());
    lc.add_layer(std::make_unique<ObstacleLayer>(grid(), ObstacleLayerParams{}));
    PointCloud pts;
    pts.xyz = {{3.0f, 2.5f, 0.3f},
               {3.0f, 2.5f, 0.02f} /* floor: no mark */,
               {1.0f, 1.0f, 2.0f} /* high */};
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

// A round table's foot plate (3 cm high) is marked from the returns on its top, an arc of cells.
// A ray to the floor behind it that passes 1.5 cm over that top proves nothing about it (the plate
// would not have stopped it); one that passes lower than top + low_clear_margin_m does (the plate
// has gone), and so does a sweep that shows its cell bare. A low mark alone (floor noise at the
// lowest ring's reach) is cleared within low_single_clear_margin_m.
TEST(ObstacleLayer, KeepsALowPartRaysPassOverAndClearsNoiseAndBareFloor) {
    using V = Eigen::Vector3f;
    auto sweep = [](LayeredCostmap& lc, std::vector<Eigen::Vector3f> xyz) {
        PointCloud pts;
        pts.xyz = std::move(xyz);
        LayerInput in;
        in.points_world = &pts;
        in.sensor_world_m = {0.51, 2.52, 0.45};  // cell (10, 50)
        lc.update(in);
    };
    const Eigen::Vector2d plate(1.42, 2.52);  // cell (28, 50)
    // The plate's edge: cells (28, 49), (28, 50), (28, 51), two returns on its top in each.
    const std::vector<V> edge = {{1.42f, 2.47f, 0.028f}, {1.43f, 2.48f, 0.03f},
                                 {1.42f, 2.52f, 0.028f}, {1.43f, 2.53f, 0.03f},
                                 {1.42f, 2.57f, 0.028f}, {1.43f, 2.58f, 0.03f}};
    const std::vector<V> alone = {edge[2], edge[3]};
    // Floor 20 cells out: over the plate's cell (18 of 20) the ray is 0.45 - 0.9 x 0.45 = 4.5 cm
    // up.
    const std::vector<V> over = {{1.52f, 2.52f, 0.0f}};
    // Floor 19 cells out: 18 of 19, 2.4 cm up, below the plate's top.
    const std::vector<V> through = {{1.47f, 2.52f, 0.0f}};
    for (double margin : {0.01, 0.05}) {
        ObstacleLayerParams p;
        p.low_clear_margin_m = margin;
        LayeredCostmap lc(grid());
        lc.add_layer(std::make_unique<ObstacleLayer>(grid(), p));
        sweep(lc, edge);
        ASSERT_EQ(*lc.master().cost_at(plate), cost::kLethal) << margin;
        sweep(lc, over);
        // 4.5 cm is 1.5 cm over the top: within a 5 cm margin (the old one) the plate is cleared.
        EXPECT_EQ(*lc.master().cost_at(plate), margin < 0.015 ? cost::kLethal : cost::kFree)
            << margin;
        sweep(lc, edge);
        sweep(lc, through);
        EXPECT_EQ(*lc.master().cost_at(plate), cost::kFree) << margin;
    }
    {
        LayeredCostmap lc(grid());
        lc.add_layer(std::make_unique<ObstacleLayer>(grid(), ObstacleLayerParams{}));
        // A mark alone: the same ray 1.5 cm over it clears it (within 5 cm).
        sweep(lc, alone);
        ASSERT_EQ(*lc.master().cost_at(plate), cost::kLethal);
        sweep(lc, over);
        EXPECT_EQ(*lc.master().cost_at(plate), cost::kFree);
        // The plate's cell seen bare (two floor returns, none above the clearance): cleared; with
        // one return on the plate's top among them: kept.
        sweep(lc, edge);
        sweep(lc, {{1.41f, 2.51f, 0.004f}, {1.44f, 2.54f, 0.008f}, {1.42f, 2.53f, 0.029f}});
        EXPECT_EQ(*lc.master().cost_at(plate), cost::kLethal);
        sweep(lc, {{1.41f, 2.51f, 0.004f}, {1.44f, 2.54f, 0.008f}});
        EXPECT_EQ(*lc.master().cost_at(plate), cost::kFree);
        EXPECT_EQ(*lc.master().cost_at({1.42, 2.47}), cost::kLethal);  // the rest of the edge
    }
    ObstacleLayerParams bad;
    bad.low_clear_margin_m = -0.01;
    EXPECT_FALSE(bad.validate().empty());
}

// The reference: Zingl's error-term Bresenham loop (the obstacle layer's walk before issue 31).
std::vector<Eigen::Vector2i> bresenham(int x, int y, int ex, int ey) {
    std::vector<Eigen::Vector2i> out;
    const int dx = std::abs(ex - x), dy = -std::abs(ey - y), sx = x < ex ? 1 : -1,
              sy = y < ey ? 1 : -1;
    int err = dx + dy;
    while (x != ex || y != ey) {
        out.emplace_back(x, y);
        const int e2 = 2 * err;
        if (e2 >= dy) err += dy, x += sx;
        if (e2 <= dx) err += dx, y += sy;
    }
    return out;
}

// The closed-form walk visits Bresenham's cells in Bresenham's order, and where blocks are empty it
// skips exactly their cells: 20,000 random rays (all octants, negative coordinates, zero length,
// ties) over random block maps, and 20 rays up to 113,000 cells long.
TEST(RayWalk, VisitsBresenhamsCellsAndSkipsOnlyEmptyBlocks) {
    Rng rng = make_rng(7);
    for (int k = 0; k < 20020; ++k) {
        const int span =
            k < 20000 ? 40 : 40000;  // the last 20: long enough that a jump needs 64-bit arithmetic
        const int x0 = static_cast<int>(uniform_int(rng, -span, span)),
                  y0 = static_cast<int>(uniform_int(rng, -span, span));
        const int x1 = static_cast<int>(uniform_int(rng, -span, span)),
                  y1 = static_cast<int>(uniform_int(rng, -span, span));
        const int block = static_cast<int>(uniform_int(rng, 1, 9));
        const double p_empty = k % 3 == 0 ? 0.0 : uniform(rng, 0.0, 1.0);
        const std::uint64_t salt = rng();
        auto empty = [&](int bx, int by) {  // a fixed random block map for this ray
            return p_empty > 0.0 &&
                   counter_uniform(salt, static_cast<std::uint64_t>((bx + 1000) * 4096 +
                                                                    (by + 1000))) < p_empty;
        };
        std::vector<Eigen::Vector2i> expected;
        for (const Eigen::Vector2i& c : bresenham(x0, y0, x1, y1)) {
            if (!empty(floor_div(c.x(), block), floor_div(c.y(), block))) expected.push_back(c);
        }
        std::vector<Eigen::Vector2i> got;
        walk_ray(x0, y0, x1, y1, block, empty, [&](int x, int y) { got.emplace_back(x, y); });
        ASSERT_EQ(got, expected) << "(" << x0 << "," << y0 << ") -> (" << x1 << "," << y1
                                 << ") block " << block;
    }
}

// A layer that asks for the whole map every update: with it the master is recomposed everywhere,
// the reference the windowed updates must equal.
class WholeMapLayer : public Layer {
  public:
    std::string name() const override { return "whole_map"; }
    void update_bounds(const Costmap& master, const LayerInput&, GridWindow& window) override {
        window.expand({0, 0, master.width, master.height});
    }
    void update_costs(Costmap&, const GridWindow&) override {}
};

// The windows are only where something changed (issue 31: obstacle cells that flipped, zones that
// appeared, moved or vanished, then inflation around them): a moving walker, a furniture leg that
// comes and goes, range noise on walls, objects moved, dropped below min_existence and added, on a
// robot that drives; every update the master equals a full recomposition, cell for cell.
TEST(LayeredCostmap, ChangedWindowsEqualAFullRecomposition) {
    Costmap walls = grid(240);  // 12 m; the room is 8 m across
    for (int i = 0; i < 160; ++i)
        walls.at(i, 0) = walls.at(0, i) = walls.at(i, 159) = cost::kLethal;
    for (int i = 40; i < 90; ++i) walls.at(120, i) = cost::kLethal;
    auto make = [&](bool reference) {
        auto lc = std::make_unique<LayeredCostmap>(grid(240));
        lc->add_layer(std::make_unique<StaticLayer>(walls));
        lc->add_layer(std::make_unique<ObstacleLayer>(grid(240), ObstacleLayerParams{}));
        lc->add_layer(std::make_unique<AffordanceLayer>(AffordanceParams{}));
        if (reference) lc->add_layer(std::make_unique<WholeMapLayer>());
        lc->add_layer(std::make_unique<InflationLayer>(InflationParams{0.25, 0.45, 3.0}));
        return lc;
    };
    const auto windowed = make(false), reference = make(true);
    Rng rng = make_rng(31);
    std::vector<ObjectEstimate> objects = {object(ObjectClass::kChair, {2.0, 5.0}, 0.5, 0.5, 0.3),
                                           object(ObjectClass::kTable, {5.0, 2.0}, 1.2, 0.8, 1.0),
                                           object(ObjectClass::kChair, {6.0, 6.0}, 0.5, 0.5, -2.0)};
    std::size_t cells_changed = 0, updates_with_small_windows = 0;
    for (int k = 0; k < 60; ++k) {
        PointCloud pts;
        // From update 45 on the robot stands and its sweeps repeat but for one leg that comes and
        // goes: the only change is that leg's cell, marked then cleared by the ray behind it.
        const bool quiet = k >= 45;
        const int at = std::min(k, 45);
        const Eigen::Vector2d robot(1.0 + 0.08 * at, 1.5 + 0.05 * at);
        for (int a = 0; a < 720; ++a) {  // a room of walls 8 m across, seen with range noise
            const double t = 2.0 * M_PI * a / 720.0;
            const Eigen::Vector2d dir(std::cos(t), std::sin(t));
            double r = 20.0;
            for (int axis = 0; axis < 2; ++axis) {
                if (dir[axis] > 1e-9) r = std::min(r, (7.9 - robot[axis]) / dir[axis]);
                if (dir[axis] < -1e-9) r = std::min(r, (0.05 - robot[axis]) / dir[axis]);
            }
            if (!quiet) r += normal(rng, 0.0, 0.01);
            for (double z : {0.02, 0.3, 0.9})
                pts.xyz.emplace_back(static_cast<float>(robot.x() + r * dir.x()),
                                     static_cast<float>(robot.y() + r * dir.y()),
                                     static_cast<float>(z));
        }
        const Eigen::Vector2d walker(3.0 + 0.05 * k, 4.0);
        for (int a = 0; a < 24 && !quiet; ++a)
            pts.xyz.emplace_back(static_cast<float>(walker.x() + 0.2 * std::cos(a * 0.26)),
                                 static_cast<float>(walker.y() + 0.2 * std::sin(a * 0.26)), 0.8f);
        if (k % 4 < 2)
            pts.xyz.emplace_back(4.0f, 5.5f, 0.3f);  // a leg seen every other pair of sweeps
        if (k % 5 == 2) objects[0].box_world.centre_m.x() += 0.1;  // a chair pulled out
        if (k % 9 == 5)
            objects[1].existence =
                objects[1].existence > 0.5 ? 0.2 : 0.9;  // below min_existence and back
        if (k == 32) objects.pop_back();                 // gone
        if (k == 41)
            objects.push_back(object(ObjectClass::kChair, {3.0, 2.5}, 0.5, 0.5, 1.0));  // new
        LayerInput in;
        in.points_world = k % 3 == 2 ? nullptr : &pts;  // every third update the objects alone
        in.sensor_world_m = {robot.x(), robot.y(), 0.45};
        in.objects = objects;
        const Costmap before = windowed->master();
        const UpdateResult w = windowed->update(in);
        reference->update(in);
        ASSERT_EQ(windowed->master().cost, reference->master().cost) << "update " << k;
        for (std::size_t i = 0; i < before.cost.size(); ++i)
            cells_changed += before.cost[i] != windowed->master().cost[i];
        if (k > 0 && (w.window.x1 - w.window.x0) * (w.window.y1 - w.window.y0) < 240 * 240 / 2)
            ++updates_with_small_windows;
    }
    EXPECT_GT(cells_changed, 500u);              // the comparison is not of two idle maps
    EXPECT_GT(updates_with_small_windows, 30u);  // and the windows are smaller than the map
}

// The obstacle layer's rays and the inflation's distance transform on several threads: the same
// map, cell for cell, as on one, on sweeps with enough returns (thousands of endpoint cells, wide
// windows) that the threads are used.
TEST(LayeredCostmap, ThreadsGiveTheSameMapAsOne) {
    auto make = [](int threads) {
        auto lc = std::make_unique<LayeredCostmap>(grid(400));
        ObstacleLayerParams obstacle;
        obstacle.threads = threads;
        lc->add_layer(std::make_unique<ObstacleLayer>(grid(400), obstacle));
        InflationParams inflation{0.25, 0.55, 3.0};
        inflation.threads = threads;
        lc->add_layer(std::make_unique<InflationLayer>(inflation));
        return lc;
    };
    const auto one = make(1), two = make(2);
    Rng rng = make_rng(7);
    std::size_t lethal = 0, cleared = 0;
    for (int k = 0; k < 12; ++k) {
        const Eigen::Vector2d sensor(8.0 + 0.3 * k, 9.0 - 0.2 * k);
        PointCloud pts;
        // Clutter everywhere (tall and low returns, most of them in cells of their own) that moves
        // from sweep to sweep: marks appear, and rays clear the last sweep's.
        for (int i = 0; i < 6000; ++i)
            pts.xyz.emplace_back(
                static_cast<float>(uniform(rng, 1.0, 19.0)),
                static_cast<float>(uniform(rng, 1.0, 19.0)),
                static_cast<float>(i % 3 == 0 ? uniform(rng, 0.0, 0.06) : uniform(rng, 0.1, 1.5)));
        LayerInput in;
        in.points_world = &pts;
        in.sensor_world_m = {sensor.x(), sensor.y(), 0.45};
        const Costmap before = one->master();
        one->update(in);
        two->update(in);
        ASSERT_EQ(one->master().cost, two->master().cost) << "update " << k;
        for (std::size_t i = 0; i < before.cost.size(); ++i) {
            lethal += one->master().cost[i] == cost::kLethal;
            cleared += before.cost[i] == cost::kLethal && one->master().cost[i] != cost::kLethal;
        }
    }
    std::cout << "[          ] " << lethal << " lethal cells over 12 updates, " << cleared
              << " cleared\n";
    EXPECT_GT(lethal, 3000u);   // the maps compared hold obstacles ...
    EXPECT_GT(cleared, 2000u);  // ... and rays cleared some of them
}

}  // namespace
}  // namespace makeway::costmap
