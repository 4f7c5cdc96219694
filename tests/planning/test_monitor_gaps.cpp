// The collision monitor's narrow gaps (bridge_gap_m), with known answers: the chair seat the
// sensor sees edge-on between its back's two posts, which a robot turning on the spot beside the
// chair sweeps a corner into.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "makeway/planning/collision_monitor.hpp"
#include "makeway/planning/gap_bridge.hpp"
#include "makeway/sim/robot.hpp"
#include "monitor_test_util.hpp"

namespace makeway::planning {
namespace {

TEST(BridgeGaps, FillsANarrowGapEveryStepAndNothingElse) {
    // Two returns 0.3 m apart: the points between them, one per 3 cm cell, none on the ends.
    const std::vector<Eigen::Vector2d> posts{{0.0, 0.0}, {0.3, 0.0}};
    const std::vector<Eigen::Vector2d> bridge = bridge_gaps(posts, 0.35, 0.03);
    ASSERT_EQ(bridge.size(), 9u);
    for (std::size_t k = 0; k < bridge.size(); ++k) {
        EXPECT_NEAR(bridge[k].x(), 0.03 * static_cast<double>(k + 1), 1e-12);
        EXPECT_EQ(bridge[k].y(), 0.0);
    }
    // A gap the robot fits through stays open; returns 2 steps apart are one surface already.
    EXPECT_TRUE(bridge_gaps({{0.0, 0.0}, {0.5, 0.0}}, 0.35, 0.03).empty());
    EXPECT_TRUE(bridge_gaps({{0.0, 0.0}, {0.06, 0.0}}, 0.35, 0.03).empty());
    // A surface seen whole (a wall, a return every 2 cm) has no gap: nothing added.
    std::vector<Eigen::Vector2d> wall;
    for (int i = 0; i <= 50; ++i) wall.emplace_back(0.02 * i, 1.0);
    EXPECT_TRUE(bridge_gaps(wall, 0.35, 0.03).empty());
    // Off: a gap no wider than two steps.
    EXPECT_TRUE(bridge_gaps(posts, 0.06, 0.03).empty());
}

// bridge_gaps by its definition, over every pair (no buckets, no bitmap): the cells of the points
// it adds.
std::set<std::pair<std::int64_t, std::int64_t>> brute_force_bridge_cells(
    const std::vector<Eigen::Vector2d>& pts, double gap_m, double step_m) {
    auto cell = [&](const Eigen::Vector2d& q) {
        return std::pair<std::int64_t, std::int64_t>(
            static_cast<std::int64_t>(std::floor(q.x() / step_m)),
            static_cast<std::int64_t>(std::floor(q.y() / step_m)));
    };
    std::set<std::pair<std::int64_t, std::int64_t>> occupied, out;
    for (const Eigen::Vector2d& q : pts) occupied.insert(cell(q));
    for (std::size_t i = 0; i < pts.size(); ++i) {
        for (std::size_t j = i + 1; j < pts.size(); ++j) {
            const Eigen::Vector2d d = pts[j] - pts[i];
            if (d.norm() <= 2.0 * step_m || d.norm() > gap_m) continue;
            bool middle_free = true;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    middle_free &=
                        !occupied.count(cell(pts[i] + 0.5 * d + step_m * Eigen::Vector2d(dx, dy)));
            if (!middle_free) continue;
            const int n = static_cast<int>(std::ceil(d.norm() / step_m));
            for (int k = 1; k < n; ++k) {
                const auto c = cell(pts[i] + d * (static_cast<double>(k) / n));
                if (!occupied.count(c)) out.insert(c);
            }
        }
    }
    return out;
}

TEST(BridgeGaps, AddsTheCellsOfItsDefinitionOnScatteredReturns) {
    // Scattered returns around the origin (negative cells too), and the same far apart (100 km:
    // the cells no bitmap holds): one point per cell of the brute force's, none twice.
    std::mt19937 rng(7);
    for (const double spread_m : {1.5, 1.0e5}) {
        std::uniform_real_distribution<double> u(-1.5, 1.5), far(-spread_m, spread_m);
        std::vector<Eigen::Vector2d> pts;
        for (int c = 0; c < 12; ++c) {  // clusters of returns, as chairs and walls give
            const Eigen::Vector2d centre(spread_m > 10.0 ? far(rng) : 0.0, 0.0);
            for (int k = 0; k < 40; ++k)
                pts.push_back(centre + 0.5 * Eigen::Vector2d(u(rng), u(rng)));
        }
        const std::vector<Eigen::Vector2d> added = bridge_gaps(pts, 0.35, 0.03);
        std::set<std::pair<std::int64_t, std::int64_t>> cells;
        for (const Eigen::Vector2d& q : added)
            EXPECT_TRUE(cells
                            .insert({static_cast<std::int64_t>(std::floor(q.x() / 0.03)),
                                     static_cast<std::int64_t>(std::floor(q.y() / 0.03))})
                            .second);
        const auto expected = brute_force_bridge_cells(pts, 0.35, 0.03);
        EXPECT_GT(expected.size(), 50u) << spread_m;  // gaps to close, not an empty answer
        EXPECT_EQ(cells, expected) << spread_m;
    }
}

// The posts (below) stay out of the padded corner's reach.
CollisionMonitorParams jackal_tight() {
    CollisionMonitorParams p = jackal();
    p.stop_padding_m = 0.01;
    return p;
}

// Two posts of a chair's back (3 returns each) 0.32 m apart on the line y = -0.31, beside a robot
// at the origin: each 0.35 m from its centre, out of the reach of its corners (0.333 m, +0.01
// padding) whatever way it turns, while the segment between them comes within 0.31 m, which the
// corner sweeps through turning clockwise: the seat.
PointCloud posts_sweep() {
    PointCloud c;
    for (const float x : {-0.16f, 0.16f}) {
        for (const float y : {-0.31f, -0.32f, -0.33f}) c.xyz.emplace_back(x, y, 0.47f);
    }
    return c;
}

// The navigator asks to turn clockwise on the spot for 3 s; the closest the footprint came to the
// seat (the segment between the posts' faces, every 5 mm) and to the posts' returns.
struct TurnOutcome {
    double seat_m = 1e9, posts_m = 1e9;
    bool stopped = false;
};
TurnOutcome turn_beside_posts(const CollisionMonitorParams& params) {
    const sim::RobotParams robot;
    CollisionMonitor monitor(params);
    const PointCloud sweep = posts_sweep();
    sim::RobotState state;
    VelocityCommand cmd;
    TurnOutcome out;
    for (int k = 0; k < 30; ++k) {
        for (int i = 0; i < 10; ++i) {  // the last command acts for one period
            state = sim::step_diff_drive(state, cmd, 0.01, robot);
            for (double x = -0.16; x <= 0.16 + 1e-9; x += 0.005)
                out.seat_m = std::min(out.seat_m, footprint_distance(state.pose, {x, -0.31}));
            for (const Eigen::Vector3f& p : sweep.xyz)
                out.posts_m = std::min(out.posts_m,
                                       footprint_distance(state.pose, p.head<2>().cast<double>()));
        }
        const MonitorResult r = monitor.filter(
            {0.1 * (k + 1), state.pose, &sweep, {0.0, -1.0}, state.v_mps, state.w_radps});
        cmd = r.command;
        out.stopped |= r.action == MonitorAction::kStop ||
                       (r.action == MonitorAction::kApproach && r.scale == 0.0);
        if (r.recovering) break;
    }
    return out;
}

TEST(CollisionMonitor, ATurnSweepingACornerBetweenTwoPostsIsStopped) {
    const sim::RobotParams r;
    const double corner = 0.5 * std::hypot(r.length_m, r.width_m);
    for (const Eigen::Vector3f& p : posts_sweep().xyz)
        ASSERT_GT(p.head<2>().norm(), corner + 0.01 + 1e-3);
    ASSERT_LT(0.31, corner);  // the corner crosses the segment between the posts

    CollisionMonitorParams open = jackal_tight();
    open.bridge_gap_m = 0.0;
    const TurnOutcome without = turn_beside_posts(open);
    EXPECT_FALSE(without.stopped);  // the posts alone are never in the way ...
    EXPECT_GT(without.posts_m, 0.0);
    EXPECT_EQ(without.seat_m, 0.0);  // ... and the corner goes through the seat

    const TurnOutcome with = turn_beside_posts(jackal_tight());
    EXPECT_TRUE(with.stopped);
    EXPECT_GT(with.seat_m, 0.0);
    EXPECT_LT(with.seat_m, 0.05);  // it turned up to the seat, not far short of it

    // Driving straight ahead, along the posts, is not held by them.
    CollisionMonitor ahead(jackal_tight());
    const PointCloud sweep = posts_sweep();
    EXPECT_EQ(ahead.filter({0.0, Pose2{}, &sweep, {0.3, 0.0}, 0.0, 0.0}).action,
              MonitorAction::kNone);
}

TEST(CollisionMonitor, ABridgeNeverClosesAGapTheRobotFitsThrough) {
    // A robot 0.25 m wide with the default bridge (0.35 m): two posts 0.32 m apart ahead, which it
    // passes between with 3.5 cm to spare on each side, stay open (the bridge is capped at the
    // footprint's width - 3 cm).
    CollisionMonitorParams p = jackal_tight();
    p.footprint_width_m = 0.25;
    ASSERT_GT(p.bridge_gap_m, 0.32);
    CollisionMonitor narrow(p);
    PointCloud posts;
    for (const float y : {-0.16f, 0.16f}) posts.xyz.emplace_back(0.45f, y, 0.3f);
    for (const float y : {-0.17f, 0.17f}) posts.xyz.emplace_back(0.45f, y, 0.3f);
    const MonitorResult r = narrow.filter({0.0, Pose2{}, &posts, {0.3, 0.0}, 0.3, 0.0});
    EXPECT_NE(r.action, MonitorAction::kStop);
    EXPECT_NE(r.action, MonitorAction::kApproach);
    EXPECT_GT(r.command.v_mps, 0.0);
}

}  // namespace
}  // namespace makeway::planning
