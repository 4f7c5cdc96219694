#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/costmap/affordance_layer.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/layered_costmap.hpp"
#include "makeway/planning/astar.hpp"
#include "makeway/planning/dwa.hpp"

namespace makeway::planning {
namespace {

// A perfect unicycle's pose after (v, w) for dt, on the exact arc: the tests' own motion model,
// independent of DWA's rollouts.
Pose2 along_arc(Pose2 pose, double v, double w, double dt) {
    if (std::abs(w) < 1e-9) {
        pose.x_m += v * dt * std::cos(pose.yaw_rad);
        pose.y_m += v * dt * std::sin(pose.yaw_rad);
    } else {
        pose.x_m += v / w * (std::sin(pose.yaw_rad + w * dt) - std::sin(pose.yaw_rad));
        pose.y_m -= v / w * (std::cos(pose.yaw_rad + w * dt) - std::cos(pose.yaw_rad));
    }
    pose.yaw_rad += w * dt;
    return pose;
}

TEST(AStar, StraightLineIsOptimal) {
    const Costmap m({0, 0}, 1.0, 10, 5);
    const PlanResult r = plan_astar(m, {0.5, 2.5}, {9.5, 2.5});
    ASSERT_EQ(r.status, PlanStatus::kOk);
    EXPECT_DOUBLE_EQ(r.cost, 9.0);
    EXPECT_EQ(r.path_m.size(), 10u);
}

TEST(AStar, DetoursAroundAWallOptimally) {
    Costmap m({0, 0}, 1.0, 10, 6);
    for (int y = 0; y < 5; ++y) m.at(5, y) = cost::kLethal;  // gap at y = 5
    const PlanResult r = plan_astar(m, {0.5, 0.5}, {9.5, 0.5});
    ASSERT_EQ(r.status, PlanStatus::kOk);
    // 8-connected optimum: 4 diagonal steps up to (4,4), a diagonal to (5,5), one down to (6,4)...
    // = from (0,0) to (5,5): 5 diagonals; from (5,5) to (9,0): 4 diagonals + 1 straight.
    EXPECT_NEAR(r.cost, 9 * std::sqrt(2.0) + 1.0, 1e-9);
    m.at(5, 5) = cost::kLethal;
    EXPECT_EQ(plan_astar(m, {0.5, 0.5}, {9.5, 0.5}).status, PlanStatus::kNoPath);
    EXPECT_EQ(plan_astar(m, {5.5, 0.5}, {9.5, 0.5}).status, PlanStatus::kStartBlocked);
    EXPECT_EQ(plan_astar(m, {0.5, 0.5}, {5.5, 2.5}).status, PlanStatus::kGoalBlocked);
    EXPECT_EQ(plan_astar(m, {0.5, 0.5}, {50, 0.5}).status, PlanStatus::kOutsideMap);
}

TEST(AStar, RespectsSoftCosts) {
    // A soft band across the direct route: cheap to cross with weight 0, avoided with a high
    // weight.
    Costmap m({0, 0}, 1.0, 11, 9);
    for (int y = 0; y < 4; ++y) m.at(5, y) = 200;
    const PlanResult cross = plan_astar(m, {0.5, 0.5}, {10.5, 0.5}, {.cost_weight = 0.0});
    EXPECT_NEAR(cross.cost, 10.0, 1e-9);
    const PlanResult around = plan_astar(m, {0.5, 0.5}, {10.5, 0.5}, {.cost_weight = 10.0});
    ASSERT_EQ(around.status, PlanStatus::kOk);
    bool crossed_band = false;
    for (const auto& p : around.path_m)
        crossed_band |= (m.cell_of(p).x() == 5 && m.cell_of(p).y() < 4);
    EXPECT_FALSE(crossed_band);
    // Crossing costs 1 + 10 * 200/252 = 8.9 extra; going round via row 4 costs 2 (4 sqrt 2 + 1) in
    // all.
    EXPECT_NEAR(around.cost, 8 * std::sqrt(2.0) + 2.0, 1e-9);
}

// path_cost is A*'s objective for any path: A*'s own paths cost what A* summed (so a plan being
// followed and a new one compare alike), a straight segment through a soft band pays for the band
// alone, and a path into a blocked cell, an unknown one or off the map is infinite.
TEST(AStar, PathCostIsTheObjectiveAStarMinimises) {
    Costmap m({0, 0}, 1.0, 11, 9);
    for (int y = 0; y < 4; ++y) m.at(5, y) = 200;
    for (const double weight : {0.0, 10.0}) {
        const AStarParams params{.cost_weight = weight};
        const PlanResult r = plan_astar(m, {0.5, 0.5}, {10.5, 0.5}, params);
        ASSERT_EQ(r.status, PlanStatus::kOk);
        EXPECT_NEAR(path_cost(m, r.path_m, params), r.cost, 1e-9) << weight;
    }
    const AStarParams params{.cost_weight = 10.0};
    // 10 m along row 0: 9 free cells and the band's cell (1 + 10 * 200 / 252 per metre).
    EXPECT_NEAR(path_cost(m, {{0.5, 0.5}, {10.5, 0.5}}, params), 9.0 + (1.0 + 2000.0 / 252.0),
                1e-9);
    // Along row 6, clear of the band: its length (in half-cell pieces).
    EXPECT_NEAR(path_cost(m, {{0.5, 6.5}, {10.5, 6.5}}, params), 10.0, 1e-9);
    m.at(8, 0) = cost::kLethal;
    EXPECT_TRUE(std::isinf(path_cost(m, {{0.5, 0.5}, {10.5, 0.5}}, params)));
    m.at(8, 6) = cost::kUnknown;
    EXPECT_TRUE(std::isinf(path_cost(m, {{0.5, 6.5}, {10.5, 6.5}}, params)));
    EXPECT_NEAR(path_cost(m, {{0.5, 6.5}, {10.5, 6.5}}, {.allow_unknown = true}),
                9.0 + (1.0 + 30.0 * cost::kMaxSoft / cost::kMaxSoft), 1e-9);
    EXPECT_TRUE(std::isinf(path_cost(m, {{0.5, 6.5}, {12.5, 6.5}}, params)));  // off the map
    EXPECT_EQ(path_cost(m, {{0.5, 6.5}}, params), 0.0);
    EXPECT_EQ(path_cost(m, {}, params), 0.0);
}

TEST(Dwa, NeverSelectsAVelocityThatCollidesWithinItsHorizon) {
    Rng rng = make_rng(21);
    const DwaParams p;
    int checked = 0;
    for (int trial = 0; trial < 60; ++trial) {
        Costmap m({0, 0}, 0.05, 80, 80);
        for (int k = 0; k < 8; ++k) {  // random obstacles
            const int cx = static_cast<int>(uniform_int(rng, 0, 79)),
                      cy = static_cast<int>(uniform_int(rng, 0, 79));
            for (int dy = -2; dy <= 2; ++dy) {
                for (int dx = -2; dx <= 2; ++dx) {
                    if (m.inside(cx + dx, cy + dy)) m.at(cx + dx, cy + dy) = cost::kLethal;
                }
            }
        }
        DwaState st;
        st.pose = {uniform(rng, 0.8, 3.2), uniform(rng, 0.8, 3.2), uniform(rng, -3.1, 3.1)};
        st.v_mps = uniform(rng, 0.0, 0.75);
        if (footprint_collides(m, st.pose, p)) continue;
        const std::vector<Eigen::Vector2d> path{{st.pose.x_m, st.pose.y_m},
                                                {uniform(rng, 0.5, 3.5), uniform(rng, 0.5, 3.5)}};
        const DwaResult r = dwa_step(m, st, path, p);
        if (!r.found) continue;
        ++checked;
        // Roll the chosen command out independently and check every pose.
        Pose2 pose = st.pose;
        const double v = r.command.v_mps, w = r.command.w_radps;
        for (int k = 0; k < 16; ++k) {
            pose = along_arc(pose, v, w, 0.1);
            ASSERT_FALSE(footprint_collides(m, pose, p)) << "trial " << trial << " step " << k;
        }
    }
    EXPECT_GT(checked, 20);
}

TEST(Dwa, HeadsForTheCarrotInFreeSpace) {
    const Costmap m({0, 0}, 0.05, 100, 100);
    DwaState st;
    st.pose = {1.0, 2.5, 0.0};
    st.v_mps = 0.5;
    const DwaResult r = dwa_step(m, st, {{1.0, 2.5}, {4.0, 2.5}}, DwaParams{});
    ASSERT_TRUE(r.found);
    EXPECT_NEAR(r.command.v_mps, 0.6, 1e-9);  // accelerating within the window
    EXPECT_NEAR(r.command.w_radps, 0.0, 0.25);
}

TEST(AStar, AZoneNeverClosesTheOnlyPassage) {
    // A wall across the map with one passage, the passage filled with the highest soft cost a zone
    // can have: the plan still goes through it, at any cost weight.
    Costmap m({0, 0}, 0.1, 60, 40);
    for (int y = 14; y < 26; ++y) {
        for (int x = 26; x < 35; ++x) m.at(x, y) = cost::kMaxSoft;  // the zone, around the passage
    }
    for (int y = 0; y < 40; ++y) {
        if (y < 18 || y >= 22)
            m.at(30, y) = cost::kLethal;  // the wall; the passage is y in [1.8, 2.2)
    }
    const PlanResult r = plan_astar(m, {0.5, 2.0}, {5.5, 2.0}, {.cost_weight = 100.0});
    ASSERT_EQ(r.status, PlanStatus::kOk);
    bool through = false;
    for (const auto& p : r.path_m) through |= m.cell_of(p).x() == 30;
    EXPECT_TRUE(through);
    // With goal tolerance: a goal inside the zone is reached at its edge.
    const PlanResult edge = plan_astar(m, {0.5, 2.0}, {3.0, 2.0}, {.cost_weight = 10.0}, 0.6);
    ASSERT_EQ(edge.status, PlanStatus::kOk);
    EXPECT_LE((edge.path_m.back() - Eigen::Vector2d(3.0, 2.0)).norm(), 0.6 + 1e-9);
    EXPECT_LT(edge.cost, plan_astar(m, {0.5, 2.0}, {3.0, 2.0}, {.cost_weight = 10.0}).cost);
    // A goal whose own cell is lethal is reachable within a radius, not without one.
    EXPECT_EQ(plan_astar(m, {0.5, 2.0}, {3.05, 0.5}, {}).status, PlanStatus::kGoalBlocked);
    EXPECT_EQ(plan_astar(m, {0.5, 2.0}, {3.05, 0.5}, {}, 0.3).status, PlanStatus::kOk);
}

TEST(Dwa, KeepsToThePlansCostEnvelopeAroundAZoneCorner) {
    // The plan turns left around the inside corner of a zone (x in [1.2, 2.35], y > 2.65); the
    // carrot lies beyond the corner, so the straight way to it cuts the zone. Within the plan's
    // envelope DWA does not; without it, it does.
    Costmap m({0, 0}, 0.05, 100, 100);
    for (int y = 0; y < 100; ++y) {
        for (int x = 0; x < 100; ++x) {
            const Eigen::Vector2d c = m.centre_of(x, y);
            if (c.x() > 1.2 && c.x() < 2.35 && c.y() > 2.65) m.at(x, y) = 120;
        }
    }
    std::vector<Eigen::Vector2d> path;
    for (double x = 1.0; x < 2.5; x += 0.05) path.emplace_back(x, 2.5);
    for (double y = 2.5; y < 4.5; y += 0.05) path.emplace_back(2.5, y);
    DwaState st;
    st.pose = {2.0, 2.5, 0.6};
    st.v_mps = 0.4;
    auto enters_zone = [&](const DwaResult& r) {
        for (const Pose2& p : r.best_rollout) {
            if (*m.cost_at({p.x_m, p.y_m}) > 0) return true;
        }
        return false;
    };
    DwaParams on;
    const DwaResult kept = dwa_step(m, st, path, on);
    ASSERT_TRUE(kept.found);
    EXPECT_FALSE(enters_zone(kept));
    DwaParams off;
    off.plan_envelope = false;
    const DwaResult cut = dwa_step(m, st, path, off);
    ASSERT_TRUE(cut.found);
    EXPECT_TRUE(enters_zone(cut));
}

// A table's zone (x in [3.05, 4.95], y up to 2.15) beside the straight way from (0.5, 2.17) to
// (7.5, 2.17). Without a margin A* rides the zone's boundary on its cost-0 cells, 2.5 cm off; with
// the margin (0.15 m) it keeps 0.15 m, and A* and DWA in a closed loop (a perfect unicycle) take
// the robot past without its centre entering the zone, at cruising speed.
TEST(AStar, ZoneMarginKeepsThePlanAndTheRobotOffTheZone) {
    ObjectEstimate table;
    table.cls = ObjectClass::kTable;
    table.box_world = {{4.0, 1.0, 0.4}, {1.6, 0.8, 0.8}, 0.0};
    const Eigen::Vector2d start(0.5, 2.17), goal(7.5, 2.17);
    for (const double margin_m : {0.0, 0.15}) {
        costmap::AffordanceParams zones;
        zones.margin_m = margin_m;
        costmap::LayeredCostmap lc(Costmap({0, 0}, 0.05, 160, 80));
        lc.add_layer(std::make_unique<costmap::AffordanceLayer>(zones));
        costmap::LayerInput in;
        in.objects = {table};
        lc.update(in);
        const Costmap& m = lc.master();
        const PlanResult plan = plan_astar(m, start, goal);
        ASSERT_EQ(plan.status, PlanStatus::kOk);
        double closest = 1e9;  // the plan's least distance from the zone along its top side
        for (const Eigen::Vector2d& q : plan.path_m) {
            if (q.x() > 3.05 && q.x() < 4.95) closest = std::min(closest, q.y() - 2.15);
        }
        if (margin_m == 0.0) {
            EXPECT_NEAR(closest, 0.025, 1e-6);
            continue;
        }
        EXPECT_GE(closest, 0.15 - 1e-6);
        DwaState st;
        st.pose = {start.x(), start.y(), 0.0};
        int inside = 0, cycles = 0;
        for (; cycles < 200 && (Eigen::Vector2d(st.pose.x_m, st.pose.y_m) - goal).norm() > 0.3;
             ++cycles) {
            const DwaResult r = dwa_step(m, st, plan.path_m, DwaParams{});
            ASSERT_TRUE(r.found);
            st.v_mps = r.command.v_mps, st.w_radps = r.command.w_radps;
            st.pose = along_arc(st.pose, st.v_mps, st.w_radps, 0.1);
            inside += costmap::in_affordance_zone(table, zones, {st.pose.x_m, st.pose.y_m});
        }
        EXPECT_EQ(inside, 0);
        EXPECT_LT(cycles, 120);  // 6.7 m at up to 0.75 m/s: arrived within 12 s
    }
}

// The true footprint (a 0.508 x 0.430 m rectangle) against the circles a round-robot check uses.
TEST(Dwa, FootprintRefusesWhatTheInscribedCircleAcceptsAndPassesWhatTheCircumscribedRefuses) {
    const DwaParams p;
    const double inscribed = 0.5 * std::min(p.footprint_length_m, p.footprint_width_m);
    const double circumscribed = 0.5 * std::hypot(p.footprint_length_m, p.footprint_width_m);
    auto circle_collides = [](const Costmap& m, const Pose2& pose,
                              double r) {  // brute force over cells
        for (int y = 0; y < m.height; ++y) {
            for (int x = 0; x < m.width; ++x) {
                if (m.at(x, y) == cost::kLethal &&
                    (m.centre_of(x, y) - Eigen::Vector2d(pose.x_m, pose.y_m)).norm() <= r)
                    return true;
            }
        }
        return false;
    };
    // One lethal cell just inside the front-left corner, 0.30 m from the centre: the inscribed
    // circle (0.215 m) misses it, the rectangle does not.
    Costmap corner({0, 0}, 0.02, 100, 100);
    const Pose2 at{1.0, 1.0, 0.0};
    const Eigen::Vector2i c = corner.cell_of({1.0 + 0.24, 1.0 + 0.19});
    corner.at(c.x(), c.y()) = cost::kLethal;
    EXPECT_FALSE(circle_collides(corner, at, inscribed));
    EXPECT_TRUE(footprint_collides(corner, at, p));
    // A 0.48 m passage along x: the circumscribed circle (0.666 m across) cannot pass, the robot
    // driving along it can; turned across it, it cannot.
    Costmap gap({0, 0}, 0.02, 150, 100);
    for (int x = 0; x < gap.width; ++x) {
        for (int y = 0; y < gap.height; ++y) {
            const double wy = gap.centre_of(x, y).y();
            if (std::abs(wy - 1.0) > 0.24) gap.at(x, y) = cost::kLethal;
        }
    }
    const Pose2 along{1.5, 1.0, 0.0}, across{1.5, 1.0, kPi / 2};
    EXPECT_TRUE(circle_collides(gap, along, circumscribed));
    EXPECT_FALSE(footprint_collides(gap, along, p));
    EXPECT_TRUE(footprint_collides(gap, across, p));
    // DWA drives through it: every rollout it picks is checked with the rectangle.
    const DwaResult r = dwa_step(gap, {{0.6, 1.0, 0.0}, 0.3, 0.0}, {{0.6, 1.0}, {2.8, 1.0}}, p);
    ASSERT_TRUE(r.found);
    EXPECT_GT(r.command.v_mps, 0.0);
    for (const Pose2& q : r.best_rollout) EXPECT_FALSE(footprint_collides(gap, q, p));
}

// The lethal-cell count only skips sampling where it proves the answer: on scattered obstacles,
// near the map's edges and outside the checker's window, every answer equals footprint_collides.
TEST(Dwa, FootprintCheckerAnswersAsTheSampledFootprint) {
    Rng rng = make_rng(7);
    DwaParams p;
    p.footprint_padding_m = 0.04;
    Costmap m({-1.0, 2.0}, 0.05, 80, 60);
    for (int k = 0; k < 25; ++k) {  // single cells and short walls
        const int x = static_cast<int>(uniform(rng, 0.0, 80.0)),
                  y = static_cast<int>(uniform(rng, 0.0, 60.0));
        const int len = uniform(rng, 0.0, 1.0) < 0.3 ? 6 : 1;
        for (int i = 0; i < len && x + i < m.width; ++i) m.at(x + i, y) = cost::kLethal;
    }
    const FootprintChecker checker(m, p, {10, 5, 70, 50});
    int free = 0, hit = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const Pose2 pose{uniform(rng, -1.3, 3.3), uniform(rng, 1.7, 5.3), uniform(rng, -kPi, kPi)};
        const bool expected = footprint_collides(m, pose, p);
        ASSERT_EQ(checker.collides(pose), expected)
            << "trial " << trial << " at " << pose.x_m << " " << pose.y_m << " " << pose.yaw_rad;
        (expected ? hit : free) += 1;
    }
    EXPECT_GT(free, 1000);  // both answers are exercised
    EXPECT_GT(hit, 1000);
}

}  // namespace
}  // namespace makeway::planning
