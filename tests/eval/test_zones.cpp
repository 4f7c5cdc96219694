// The unavoidable part of risk (known answers on hand-drawn grids), and the robot's body model:
// a part the robot can hit is a part the costmap sees.
#include <gtest/gtest.h>

#include "makeway/common/random.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/eval/unavoidable_risk.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/mesh_primitives.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::eval {
namespace {

sim::NavGrid open_grid(int w, int h, double res = 1.0) {
    sim::NavGrid g;
    g.width = w;
    g.height = h;
    g.resolution_m = res;
    g.blocked.assign(static_cast<std::size_t>(w) * h, 0);
    return g;
}

TEST(UnavoidableRisk, ACorridorThatIsAllZoneCostsItsWidth) {
    // One row of 10 cells; cells 3, 4, 5 are zone. Steps count half in each cell: 0.5 + 1 + 1 +
    // 0.5.
    const sim::NavGrid g = open_grid(10, 1);
    std::vector<std::uint8_t> zone(10, 0);
    zone[3] = zone[4] = zone[5] = 1;
    const LeastRiskRoute r = least_risk_route(g, zone, {0.5, 0.5}, {{{9.5, 0.5}, 0.0}});
    ASSERT_TRUE(r.reachable);
    EXPECT_DOUBLE_EQ(r.zone_length_m, 3.0);
    EXPECT_DOUBLE_EQ(r.length_m, 9.0);
    EXPECT_EQ(r.cells_m.size(), 10u);
}

TEST(UnavoidableRisk, TakesTheDetourThatAvoidsTheZoneAndTheShortestSuch) {
    // 11 x 5 cells; a zone wall at x = 5 from y = 0 to 3, open at y = 4: the route around it has no
    // zone, and among such routes the shortest: 4 diagonals up, 4 down, 2 straight = 8 sqrt 2 + 2.
    const sim::NavGrid g = open_grid(11, 5);
    std::vector<std::uint8_t> zone(55, 0);
    for (int y = 0; y < 4; ++y) zone[y * 11 + 5] = 1;
    const LeastRiskRoute r = least_risk_route(g, zone, {0.5, 0.5}, {{{10.5, 0.5}, 0.0}});
    ASSERT_TRUE(r.reachable);
    EXPECT_DOUBLE_EQ(r.zone_length_m, 0.0);
    EXPECT_NEAR(r.length_m, 8 * std::sqrt(2.0) + 2.0, 1e-9);
    // Closed at the top too (y = 4 blocked): the zone must be crossed, by one straight step's
    // worth.
    sim::NavGrid closed = g;
    closed.blocked[4 * 11 + 5] = 1;
    const LeastRiskRoute c = least_risk_route(closed, zone, {0.5, 0.5}, {{{10.5, 0.5}, 0.0}});
    ASSERT_TRUE(c.reachable);
    EXPECT_DOUBLE_EQ(c.zone_length_m, 1.0);
    EXPECT_DOUBLE_EQ(c.length_m, 10.0);
}

TEST(UnavoidableRisk, LegsAndTolerances) {
    // The goal stands inside a zone 2 cells deep: with tolerance 0 the route enters 2.5 cells of
    // it; a tolerance of 3 cells ends the route before the zone.
    const sim::NavGrid g = open_grid(12, 1);
    std::vector<std::uint8_t> zone(12, 0);
    zone[9] = zone[10] = zone[11] = 1;
    EXPECT_DOUBLE_EQ(least_risk_route(g, zone, {0.5, 0.5}, {{{11.5, 0.5}, 0.0}}).zone_length_m,
                     2.5);
    const LeastRiskRoute tol = least_risk_route(g, zone, {0.5, 0.5}, {{{11.5, 0.5}, 3.0}});
    EXPECT_DOUBLE_EQ(tol.zone_length_m, 0.0);
    EXPECT_DOUBLE_EQ(tol.length_m, 8.0);
    // Through a waypoint at the far end and back: the zone twice, 2.5 each way.
    const LeastRiskRoute there_and_back =
        least_risk_route(g, zone, {0.5, 0.5}, {{{11.5, 0.5}, 0.0}, {{0.5, 0.5}, 0.0}});
    EXPECT_DOUBLE_EQ(there_and_back.zone_length_m, 5.0);
    EXPECT_DOUBLE_EQ(there_and_back.length_m, 22.0);
    EXPECT_EQ(there_and_back.cells_m.size(), 23u);
    // Unreachable: a wall across the row.
    sim::NavGrid walled = g;
    walled.blocked[6] = 1;
    EXPECT_FALSE(least_risk_route(walled, zone, {0.5, 0.5}, {{{11.5, 0.5}, 0.0}}).reachable);
}

TEST(UnavoidableRisk, MatchesBruteForceOnRandomGrids) {
    // Brute force: Bellman-Ford style relaxation to a fixed point with the same lexicographic cost.
    Rng rng = make_rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        sim::NavGrid g = open_grid(9, 7);
        std::vector<std::uint8_t> zone(63, 0);
        for (int i = 0; i < 63; ++i) {
            g.blocked[i] = bernoulli(rng, 0.2);
            zone[i] = bernoulli(rng, 0.3);
        }
        g.blocked[0] = g.blocked[62] = 0;
        std::vector<std::pair<double, double>> best(63, {1e18, 1e18});
        best[0] = {0.0, 0.0};
        for (bool changed = true; changed;) {
            changed = false;
            for (int i = 0; i < 63; ++i) {
                if (g.blocked[i] || best[i].first >= 1e18) continue;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int x = i % 9 + dx, y = i / 9 + dy;
                        if ((!dx && !dy) || g.is_blocked(x, y)) continue;
                        const double step = (dx && dy) ? std::sqrt(2.0) : 1.0;
                        const std::pair<double, double> c{
                            best[i].first + 0.5 * step * (zone[i] + zone[y * 9 + x]),
                            best[i].second + step};
                        if (c.first < best[y * 9 + x].first - 1e-12 ||
                            (std::abs(c.first - best[y * 9 + x].first) <= 1e-12 &&
                             c.second < best[y * 9 + x].second - 1e-12)) {
                            best[y * 9 + x] = c;
                            changed = true;
                        }
                    }
                }
            }
        }
        const LeastRiskRoute r = least_risk_route(g, zone, {0.5, 0.5}, {{{8.5, 6.5}, 0.0}});
        ASSERT_EQ(r.reachable, best[62].first < 1e18) << trial;
        if (!r.reachable) continue;
        EXPECT_NEAR(r.zone_length_m, best[62].first, 1e-9) << trial;
        EXPECT_NEAR(r.length_m, best[62].second, 1e-9) << trial;
    }
}

// A 3 cm foot plate (a table's): the robot cannot roll over it, so the simulator counts a
// collision, and the obstacle layer marks it from a sweep; nothing on the bare floor is marked.
// A 6 x 6 m room, nothing in it.
sim::Scene empty_room() {
    sim::Scene scene;
    scene.floor_min_m = {-4.0, -4.0};
    scene.floor_max_m = {4.0, 4.0};
    scene.walls = {{{-3.0, -3.0}, {3.0, -3.0}, 0.2, 3.0},
                   {{3.0, -3.0}, {3.0, 3.0}, 0.2, 3.0},
                   {{3.0, 3.0}, {-3.0, 3.0}, 0.2, 3.0},
                   {{-3.0, 3.0}, {-3.0, -3.0}, 0.2, 3.0}};
    return scene;
}

// One sweep (world frame, from a sensor standing at T_world_sensor) into the obstacle layer.
void update_from_sweep(costmap::ObstacleLayer& layer, const Costmap& geometry,
                       const PointCloud& world_points, const Isometry3& T_world_sensor) {
    Costmap master = geometry;
    GridWindow window;
    costmap::LayerInput in;
    in.points_world = &world_points;
    in.sensor_world_m = T_world_sensor.translation();
    layer.update_bounds(master, in, window);
}

TEST(BodyModel, ALowPartTheRobotCanHitIsSeenByTheCostmap) {
    sim::Scene scene = empty_room();
    sim::SceneObject plate;
    plate.id = 1;
    plate.cls = ObjectClass::kTable;
    plate.pose = {1.5, 0.0, 0.0};
    scene.objects = {plate};
    sim::ObjectModel model;
    sim::add_box(model.mesh_object, {0.0, 0.0, 0.015}, {0.5, 0.5, 0.03});
    model.box_object = {{0.0, 0.0, 0.015}, {0.5, 0.5, 0.03}, 0.0};
    const sim::RobotParams robot;
    const sim::CollisionChecker checker(scene, {model}, robot);
    const Pose2 over_plate{1.5 - 0.25 - 0.2, 0.0,
                           0.0};  // the footprint's front 5 cm over the plate
    EXPECT_TRUE(checker.collides(over_plate, 0.0));
    sim::RobotParams high = robot;
    high.ground_clearance_m = 0.04;  // a robot that rolls over 4 cm
    EXPECT_FALSE(sim::CollisionChecker(scene, {model}, high).collides(over_plate, 0.0));

    // One sweep from 1.3 m before the plate's centre; the obstacle layer with the same body.
    sim::World world(scene, {model});
    sim::LidarParams lidar;
    const Isometry3 T_world_sensor = make_T_xyz_yaw({0.2, 0.0, robot.lidar_height_m}, 0.0);
    const PointCloud sweep = sim::simulate_sweep(
        world, lidar, [&](double) { return T_world_sensor; }, 0.0, 3, 0);
    const PointCloud world_points =
        perception::deskew_to_world({sweep, 0.0, 0.1, T_world_sensor, T_world_sensor});
    auto marked_on_plate = [&](const BodyHeights& body) {
        const Costmap geometry({-4.0, -4.0}, 0.05, 160, 160);
        costmap::ObstacleLayer layer(geometry, {.body = body});
        update_from_sweep(layer, geometry, world_points, T_world_sensor);
        int marked = 0;
        for (int y = 0; y < 160; ++y) {
            for (int x = 0; x < 160; ++x) {
                const Eigen::Vector2d c = geometry.centre_of(x, y);
                const bool on_plate = std::abs(c.x() - 1.5) < 0.25 && std::abs(c.y()) < 0.25;
                if (layer.grid().at(x, y) == cost::kLethal) {
                    EXPECT_TRUE(on_plate || std::abs(c.x()) > 2.8 || std::abs(c.y()) > 2.8)
                        << c.transpose();  // nothing on the bare floor
                    marked += on_plate;
                }
            }
        }
        return marked;
    };
    EXPECT_GE(marked_on_plate(robot.body()), 5);
    EXPECT_EQ(marked_on_plate(high.body()), 0);
}

TEST(BodyModel, LowMarksNeedTwoReturnsAndSurviveRaysPassingOverThem) {
    const Costmap geometry({0.0, 0.0}, 0.05, 100, 100);
    costmap::ObstacleLayer layer(geometry, {});
    Costmap master = geometry;
    costmap::LayerInput in;
    PointCloud pts;
    in.points_world = &pts;
    in.sensor_world_m = {0.5, 2.5, 0.45};
    auto update = [&] {
        GridWindow w;
        layer.update_bounds(master, in, w);
    };
    pts.xyz = {{2.0f, 2.51f, 0.03f}};  // one low return: floor noise until another joins it
    update();
    EXPECT_EQ(*layer.grid().cost_at({2.0, 2.51}), cost::kFree);
    pts.xyz = {{2.0f, 2.51f, 0.03f},
               {2.01f, 2.52f, 0.025f},
               {2.02f, 2.53f, 0.01f},
               {2.03f, 2.53f, 0.005f},
               {2.04f, 2.52f, 0.003f}};
    update();
    EXPECT_EQ(*layer.grid().cost_at({2.0, 2.51}),
              cost::kFree);  // two of five above the clearance: a noisy floor
    pts.xyz = {{2.0f, 2.51f, 0.03f},
               {2.01f, 2.52f, 0.025f},
               {2.02f, 2.53f, 0.01f},
               {4.0f, 1.0f, 0.03f},
               {4.01f, 1.01f, 0.03f}};
    update();
    EXPECT_EQ(*layer.grid().cost_at({2.0, 2.51}), cost::kLethal);
    EXPECT_EQ(*layer.grid().cost_at({4.0, 1.0}), cost::kFree);  // low and 3.8 m away: not trusted
    // A ray to a wall behind passes 0.3 m above the runner: it proves nothing about it.
    pts.xyz = {{4.5f, 2.5f, 0.3f}};
    update();
    EXPECT_EQ(*layer.grid().cost_at({2.0, 2.51}), cost::kLethal);
    // A ray to the floor 4 cells behind it passes 5.3 cm up, 2.3 cm over its 3 cm top. The mark is
    // alone (no low mark beside it, as floor noise raises them): cleared within 5 cm
    // (low_single_clear_margin_m; a part of several cells is kept: tests/costmap).
    pts.xyz = {{2.2f, 2.5f, 0.0f}};
    update();
    EXPECT_EQ(*layer.grid().cost_at({2.0, 2.51}), cost::kFree);
}

// People in the costmap: a walker crossing 1.5 m ahead is marked from the live sweep while it
// stands there and cleared by the rays of a later sweep once it has walked on (issue 29).
TEST(BodyModel, AWalkerIsMarkedWhileThereAndClearedWhenGone) {
    sim::Scene scene = empty_room();
    scene.walkers = {
        {{{1.5, -2.0}, {1.5, 2.0}}, 1.0, 0.0}};  // at (1.5, 0) at t = 2 s, at (1.5, 2) at t = 4 s
    sim::World world(scene, {});
    const sim::RobotParams robot;
    const Isometry3 T_world_sensor = make_T_xyz_yaw({0.0, 0.0, robot.lidar_height_m}, 0.0);
    const Costmap geometry({-4.0, -4.0}, 0.05, 160, 160);
    costmap::ObstacleLayer layer(geometry, {.body = robot.body()});
    auto sweep_at = [&](double t, std::uint64_t k) {
        const PointCloud sweep = sim::simulate_sweep(
            world, {}, [&](double) { return T_world_sensor; }, t, 3, k);
        update_from_sweep(
            layer, geometry,
            perception::deskew_to_world({sweep, t, 0.1, T_world_sensor, T_world_sensor}),
            T_world_sensor);
    };
    auto marked_near = [&](const Eigen::Vector2d& p) {
        int n = 0;
        for (int y = 0; y < 160; ++y) {
            for (int x = 0; x < 160; ++x)
                n += layer.grid().at(x, y) == cost::kLethal &&
                     (geometry.centre_of(x, y) - p).norm() < 0.35;
        }
        return n;
    };
    sweep_at(1.95, 0);
    EXPECT_GE(marked_near({1.5, 0.0}), 3);
    sweep_at(3.95, 1);
    EXPECT_EQ(marked_near({1.5, 0.0}), 0);
    EXPECT_GE(marked_near({1.5, 2.0}), 1);  // where it stands now
}

}  // namespace
}  // namespace makeway::eval
