// Giving way to what the robot knows is moving (the collision monitor's give_way_horizon_s), with
// known answers: the geometry, and a chair someone pulls into the side of a robot that waits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/angles.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/planning/give_way.hpp"
#include "makeway/sim/robot.hpp"
#include "monitor_test_util.hpp"

namespace makeway::planning {
namespace {

Polygon2 square(const Eigen::Vector2d& centre, double half) {
    return {centre + Eigen::Vector2d(-half, -half), centre + Eigen::Vector2d(half, -half),
            centre + Eigen::Vector2d(half, half), centre + Eigen::Vector2d(-half, half)};
}

TEST(GiveWay, RectangleToPolygonDistanceHasKnownAnswers) {
    const Eigen::Vector2d half(0.25, 0.2);
    const Polygon2 ahead = square({0.6, 0.0}, 0.1);  // its near side 0.5 m ahead of the centre
    EXPECT_NEAR(rectangle_polygon_distance({}, half, ahead), 0.25, 1e-12);
    // Turned a quarter, the rectangle's half width faces it.
    EXPECT_NEAR(rectangle_polygon_distance({0.0, 0.0, kPi / 2}, half, ahead), 0.3, 1e-12);
    // Diagonal: corner to corner.
    EXPECT_NEAR(rectangle_polygon_distance({}, half, square({0.4, 0.35}, 0.05)),
                std::hypot(0.1, 0.1), 1e-12);
    // Either vertex order; moved with the rectangle's pose.
    Polygon2 clockwise = ahead;
    std::reverse(clockwise.begin(), clockwise.end());
    EXPECT_NEAR(rectangle_polygon_distance({}, half, clockwise), 0.25, 1e-12);
    EXPECT_NEAR(rectangle_polygon_distance({0.2, 0.0, 0.0}, half, ahead), 0.05, 1e-12);
    // Overlapping: minus the shortest shift that parts them. Crossing like a plus sign (no vertex
    // of either inside the other): the bar leaves sideways, 0.25 + 0.05.
    const Polygon2 bar{{-0.05, -1.0}, {0.05, -1.0}, {0.05, 1.0}, {-0.05, 1.0}};
    EXPECT_NEAR(rectangle_polygon_distance({}, half, bar), -0.3, 1e-12);
    // Inside (out across the nearer, long side: 0.2 + 0.05), or holding it whole (2 - 0.2 + 0.4).
    EXPECT_NEAR(rectangle_polygon_distance({}, half, square({0.0, 0.0}, 0.05)), -0.25, 1e-12);
    EXPECT_NEAR(rectangle_polygon_distance({}, half, square({0.0, 0.0}, 2.0)), -2.2, 1e-12);
    // Over a corner by 3 cm and 4 cm: out the shorter way. Turned 45 degrees under a diamond (a
    // square in the rectangle's frame) whose lowest vertex is 0.18 m up: 0.2 - 0.18 cos 45 deg.
    EXPECT_NEAR(rectangle_polygon_distance({}, half, square({0.32, 0.26}, 0.1)), -0.03, 1e-12);
    EXPECT_NEAR(rectangle_polygon_distance({0.0, 0.0, kPi / 4}, half,
                                           {{0.0, 0.18}, {-0.1, 0.28}, {0.0, 0.38}, {0.1, 0.28}}),
                -(0.2 - 0.18 * std::sqrt(0.5)), 1e-12);
    // Just touching: 0.
    EXPECT_NEAR(rectangle_polygon_distance({}, half, square({0.35, 0.0}, 0.1)), 0.0, 1e-12);
    EXPECT_TRUE(std::isinf(rectangle_polygon_distance({}, half, {})));
}

std::vector<std::pair<double, Pose2>> standing(double horizon_s) {
    std::vector<std::pair<double, Pose2>> poses;
    for (int k = 0; k * 0.05 <= horizon_s + 1e-9; ++k) poses.emplace_back(0.05 * k, Pose2{});
    return poses;
}

TEST(GiveWay, ClearanceOfAMoverComingAtAStandingRobot) {
    const Eigen::Vector2d half(0.25, 0.2);
    // A 0.4 m square whose near side is 0.3 m left of the footprint, coming at 0.2 m/s: within
    // 5 cm after 1.25 s, touching after 1.5 s.
    const MovingOutline coming{square({0.0, 0.7}, 0.2), {0.0, -0.2}};
    const Clearance c = clearance_over(standing(2.0), half, {coming}, 0.05);
    EXPECT_NEAR(c.within_s, 1.25, 1e-9);
    EXPECT_NEAR(c.least_m, -0.1, 1e-9);  // 0.4 m travelled: 0.1 m into the footprint
    EXPECT_NEAR(c.final_m, -0.1, 1e-9);
    // Over a shorter horizon it stays out of the margin.
    const Clearance early = clearance_over(standing(1.0), half, {coming}, 0.05);
    EXPECT_TRUE(std::isinf(early.within_s));
    EXPECT_NEAR(early.least_m, 0.1, 1e-9);
    EXPECT_TRUE(early.better_than(c));
    EXPECT_FALSE(c.better_than(early));
    // Going away, or nothing moving: never within the margin.
    const Clearance going =
        clearance_over(standing(2.0), half, {{coming.outline, {0.0, 0.2}}}, 0.05);
    EXPECT_TRUE(std::isinf(going.within_s));
    EXPECT_NEAR(going.least_m, 0.3, 1e-9);
    const Clearance none = clearance_over(standing(2.0), half, {}, 0.05);
    EXPECT_TRUE(std::isinf(none.within_s) && std::isinf(none.least_m));
}

// A chair seat 0.45 m square, its near side 0.3 m left of a robot the navigator holds still (it
// waits for its plan), pulled toward it at 0.17 m/s for 3 s (0.51 m: into the robot), then left.
// The sweep shows the chair's outline at seat height (and a wall 0.2 m behind the robot); the
// Controller hands the chair in as a mover while it moves. The least distance between the chair
// and the footprint, the give-way cycles, and where the robot ended.
struct PullOutcome {
    double closest_m = std::numeric_limits<double>::infinity();
    int give_way_cycles = 0;
    Pose2 end;
};

PullOutcome pulled_into(double horizon_s, bool wall_behind, const VelocityCommand& asked = {},
                        double box_grow_m = 0.0) {
    const sim::RobotParams robot;
    CollisionMonitorParams p = jackal();
    p.give_way_horizon_s = horizon_s;
    CollisionMonitor monitor(p);
    sim::RobotState state;
    VelocityCommand cmd;
    const double side = 0.5 * robot.width_m, half = 0.225, speed = 0.17, pull_s = 3.0;
    auto chair_at = [&](double t) {
        return square({0.0, side + 0.3 + half - speed * std::min(t, pull_s)}, half);
    };
    auto outline = [](const Polygon2& poly, double step) {
        std::vector<Eigen::Vector2d> pts;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
            const int n = static_cast<int>(std::ceil((b - a).norm() / step));
            for (int k = 0; k < n; ++k) pts.push_back(a + (b - a) * (static_cast<double>(k) / n));
        }
        return pts;
    };
    PullOutcome out;
    for (int k = 0; k < 60; ++k) {
        const double t = 0.1 * k;
        for (int i = 0; i < 10; ++i) {
            state = sim::step_diff_drive(state, cmd, 0.01, robot);
            for (const Eigen::Vector2d& q : outline(chair_at(t + 0.01 * (i + 1)), 0.005))
                out.closest_m = std::min(out.closest_m, footprint_distance(state.pose, q));
        }
        std::vector<Eigen::Vector2d> seen = outline(chair_at(t + 0.1), 0.02);
        if (wall_behind) {
            for (double y = -2.0; y <= 2.0; y += 0.02)
                seen.emplace_back(-0.5 * robot.length_m - 0.2, y);
        }
        PointCloud sweep;
        for (const Eigen::Vector2d& q : seen)
            sweep.xyz.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()), 0.45f);
        std::vector<MovingOutline> movers;
        if (t + 0.1 < pull_s) {  // the known box: box_grow_m larger than the chair all round
            Polygon2 box = chair_at(t + 0.1);
            const Eigen::Vector2d c = 0.25 * (box[0] + box[1] + box[2] + box[3]);
            for (Eigen::Vector2d& q : box) q += (q - c).cwiseSign() * box_grow_m;
            movers.push_back({box, {0.0, -speed}});
        }
        const MonitorResult r = monitor.filter({t + 0.1, state.pose, &sweep, asked, state.v_mps,
                                                state.w_radps, nullptr, nullptr, &movers});
        out.give_way_cycles += r.action == MonitorAction::kGiveWay ? 1 : 0;
        cmd = r.command;
    }
    out.end = state.pose;
    return out;
}

TEST(GiveWay, ARobotHeldStillMovesOffBeforeAPulledChairReachesIt) {
    // Without: the robot waits and the chair is pulled into its side.
    const PullOutcome off = pulled_into(0.0, false);
    EXPECT_EQ(off.closest_m, 0.0);
    EXPECT_EQ(off.give_way_cycles, 0);
    // With a 2 s horizon it moves off (straight back: the first candidate that keeps clear) and
    // is never touched.
    const PullOutcome on = pulled_into(2.0, false);
    EXPECT_GT(on.closest_m, 0.0);
    EXPECT_GT(on.give_way_cycles, 0);
    EXPECT_LT(on.end.x_m, -0.4);
    // A wall 0.2 m behind it: the stop check refuses backing into it, so it moves off forward.
    const PullOutcome walled = pulled_into(2.0, true);
    EXPECT_GT(walled.closest_m, 0.0);
    EXPECT_GT(walled.end.x_m, 0.4);
}

TEST(GiveWay, ANavigatorTurningIntoTheChairsWayStillGetsOut) {
    // The navigator keeps asking to creep forward turning left, into the chair's way (DWA turning
    // toward its plan): without giving way the robot meets the chair, with it the way off wins.
    const VelocityCommand into{0.1, 0.6};
    const PullOutcome off = pulled_into(0.0, false, into);
    EXPECT_EQ(off.closest_m, 0.0);
    const PullOutcome on = pulled_into(2.0, false, into);
    EXPECT_GT(on.closest_m, 0.0);
    EXPECT_GT(on.give_way_cycles, 0);
}

TEST(GiveWay, ABoxAlreadyOnTheFootprintStillMovesTheRobotOff) {
    // The known box is 0.35 m larger all round than the chair (a map's box around a chair's legs
    // and arms): it lies 5 cm over the footprint while the chair is still 0.3 m off, so every way
    // off is within the margin from the start and, as before, none was better than waiting (the
    // least distance of each is now's). The one that ends farther out wins: the robot backs off.
    const PullOutcome on = pulled_into(2.0, false, {}, 0.35);
    EXPECT_GT(on.closest_m, 0.0);
    EXPECT_GT(on.give_way_cycles, 0);
    EXPECT_LT(on.end.x_m, -0.4);
    // Of two motions within the margin from the start, the one that ends farther out; later
    // within the margin beats that.
    const Clearance stays{-0.05, 0.0, -0.05}, leaves{-0.05, 0.0, 0.2}, later{-0.3, 0.5, -0.3};
    EXPECT_TRUE(leaves.better_than(stays));
    EXPECT_FALSE(stays.better_than(leaves));
    EXPECT_TRUE(later.better_than(leaves));
}

TEST(GiveWay, AMoverThatStaysClearLeavesTheCommandAlone) {
    CollisionMonitorParams p = jackal();
    p.give_way_horizon_s = 2.0;
    CollisionMonitor monitor(p);
    const PointCloud empty;
    // A chair 1 m to the left going away; one ahead pulled across the way the robot drives (it
    // would meet the robot driving on, not the robot standing: the zones' business, not a reason
    // to move off).
    const std::vector<MovingOutline> movers{{square({0.0, 1.0}, 0.225), {0.0, 0.17}},
                                            {square({1.0, 0.6}, 0.225), {0.0, -0.17}}};
    const MonitorResult r =
        monitor.filter({0.1, Pose2{}, &empty, {0.3, 0.0}, 0.3, 0.0, nullptr, nullptr, &movers});
    EXPECT_EQ(r.action, MonitorAction::kNone);
    EXPECT_EQ(r.command.v_mps, 0.3);
    EXPECT_EQ(r.command.w_radps, 0.0);
}

}  // namespace
}  // namespace makeway::planning
