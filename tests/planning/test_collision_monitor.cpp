// The collision monitor with known answers: closed loops on the simulator's own drive model (the
// command acts one control period after the sweep it was decided on, as in bench nav), and single
// checks whose zones are worked out by hand (people: test_monitor_walkers.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/sim/robot.hpp"
#include "monitor_test_util.hpp"

namespace makeway::planning {
namespace {

// A box's outline (centre, half size), sampled every 2 cm at heights the body can hit.
std::vector<Eigen::Vector2d> box_outline(const Eigen::Vector2d& c, const Eigen::Vector2d& h) {
    std::vector<Eigen::Vector2d> out;
    for (double s = -1.0; s <= 1.0 + 1e-9; s += 0.02 / h.x())
        out.push_back(c + Eigen::Vector2d(s * h.x(), -h.y())),
            out.push_back(c + Eigen::Vector2d(s * h.x(), h.y()));
    for (double s = -1.0; s <= 1.0 + 1e-9; s += 0.02 / h.y())
        out.push_back(c + Eigen::Vector2d(-h.x(), s * h.y())),
            out.push_back(c + Eigen::Vector2d(h.x(), s * h.y()));
    return out;
}

TEST(CollisionMonitor, ABoxAppearingOneMetreAheadAtFullSpeedIsNeverTouched) {
    const sim::RobotParams robot;
    for (const double blind_m : {0.0, 0.75}) {  // with and without the sensor's blind ring
        CollisionMonitor monitor(jackal());
        sim::RobotState state;
        state.v_mps = robot.max_v_mps;
        VelocityCommand cmd{robot.max_v_mps, 0.0};
        std::vector<Eigen::Vector2d> box;
        double closest = 1e9;
        bool stopped = false;
        for (int k = 0; k < 60; ++k) {
            const double t = 0.1 * k;
            for (int i = 0; i < 10; ++i) {  // the last command acts for one period
                state = sim::step_diff_drive(state, cmd, 0.01, robot);
                for (const auto& p : box)
                    closest = std::min(closest, footprint_distance(state.pose, p));
            }
            if (k == 5) {  // the box appears 1 m ahead of the bumper
                box = box_outline({state.pose.x_m + 0.5 * robot.length_m + 1.0 + 0.2, 0.0},
                                  {0.2, 0.3});
            }
            const PointCloud sweep = sweep_of(box, state.pose, blind_m);
            // The navigator keeps asking for full speed; the monitor alone must stop the robot.
            const MonitorResult r = monitor.filter(
                {t + 0.1, state.pose, &sweep, {robot.max_v_mps, 0.0}, state.v_mps, state.w_radps});
            cmd = r.command;
            stopped |= r.action == MonitorAction::kStop ||
                       (r.action == MonitorAction::kApproach && r.scale == 0.0);
            if (r.recovering) break;
        }
        EXPECT_TRUE(stopped) << blind_m;
        EXPECT_GT(closest, 0.0) << blind_m;
        EXPECT_LT(closest, 0.5) << blind_m;  // it stopped near the box, not far short of it
    }
}

TEST(CollisionMonitor, SlowdownZoneCapsTheSpeed) {
    const CollisionMonitor monitor(jackal());
    const double front = 0.254, side = 0.215;
    // Ahead, 0.55 m from the bumper at 0.6 m/s: beyond the stop zone (latency 0.2 s + braking
    // 0.18 m = 0.30 m, + 4 cm) and the approach check (contact in 0.85 s > 0.8 s), inside the
    // slowdown zone (0.30 + 0.3 s x 0.6 m/s + 10 cm = 0.58 m).
    const std::vector<Eigen::Vector2d> ahead{{front + 0.55, 0.0}, {front + 0.55, 0.02}};
    const MonitorResult a = monitor.check({0.6, 0.12}, ahead);
    EXPECT_EQ(a.action, MonitorAction::kSlowdown);
    EXPECT_NEAR(a.command.v_mps, 0.45, 1e-12);  // 60 % of the top speed, on the same arc
    EXPECT_NEAR(a.command.w_radps, 0.09, 1e-12);
    EXPECT_EQ(monitor.check({0.3, 0.0}, ahead).command.v_mps,
              0.3);  // slow enough: the zone is shorter
    // Beside the path, 7 cm out from the side: only the slowdown zone's padding reaches it.
    const std::vector<Eigen::Vector2d> beside{{front + 0.3, side + 0.07},
                                              {front + 0.32, side + 0.07}};
    const MonitorResult b = monitor.check({0.6, 0.0}, beside);
    EXPECT_EQ(b.action, MonitorAction::kSlowdown);
    EXPECT_NEAR(b.command.v_mps, 0.45, 1e-12);
    // Nothing near: the command passes unchanged; beside the robot and behind it, nothing closes
    // in.
    EXPECT_EQ(monitor.check({0.5, 0.1}, {{5.0, 5.0}, {5.0, 5.02}}).action, MonitorAction::kNone);
    const std::vector<Eigen::Vector2d> alongside{
        {0.0, side + 0.05}, {0.02, side + 0.05}, {-front - 0.05, 0.0}, {-front - 0.05, 0.02}};
    const MonitorResult c = monitor.check({0.5, 0.0}, alongside);
    EXPECT_EQ(c.action, MonitorAction::kNone);
    EXPECT_NEAR(c.command.v_mps, 0.5, 1e-12);
    // Just ahead, within the braking distance: stop.
    EXPECT_EQ(monitor.check({0.5, 0.0}, {{front + 0.15, 0.0}, {front + 0.15, 0.02}}).action,
              MonitorAction::kStop);
    // Touching the bumper: forward is stopped, backing away is not.
    const std::vector<Eigen::Vector2d> touching{{front + 0.01, 0.0}, {front + 0.01, 0.05}};
    EXPECT_EQ(monitor.check({0.3, 0.0}, touching).command.v_mps, 0.0);
    EXPECT_EQ(monitor.check({-0.15, 0.0}, touching).action, MonitorAction::kNone);
    // One return is not enough (min_points 2): sensor noise does not stop the robot.
    EXPECT_EQ(monitor.check({0.5, 0.0}, {{front + 0.15, 0.0}}).action, MonitorAction::kNone);
}

TEST(CollisionMonitor, ApproachKeepsContactAtLeastTimeBeforeCollisionAway) {
    CollisionMonitorParams p = jackal();
    p.slowdown_ratio = 1.0;  // the approach check alone
    const CollisionMonitor monitor(p);
    // 0.58 m from the bumper at full speed (0.75 m/s): beyond the stop zone (0.2 s latency + 0.28 m
    // braking + 4 cm = 0.47 m), but contact in 0.72 s, under time_before_collision_s (0.8 s).
    const double gap = 0.58;
    const MonitorResult r = monitor.check({0.75, 0.3}, {{0.254 + gap, -0.01}, {0.254 + gap, 0.01}});
    EXPECT_EQ(r.action, MonitorAction::kApproach);
    ASSERT_GT(r.scale, 0.0);
    ASSERT_LT(r.scale, 1.0);
    EXPECT_NEAR(r.command.w_radps / r.command.v_mps, 0.3 / 0.75, 1e-12);  // the same arc, slower
    // Straight ahead: contact (gap less the padding) at the scaled speed takes
    // time_before_collision_s, to within one step of the arc's sampling.
    const MonitorResult straight =
        monitor.check({0.75, 0.0}, {{0.254 + gap, -0.01}, {0.254 + gap, 0.01}});
    const double v = straight.command.v_mps;
    EXPECT_NEAR((gap - p.stop_padding_m) / v, p.time_before_collision_s,
                p.simulation_time_step_s * 0.75 / v + 1e-9);
    // Far enough: untouched.
    EXPECT_EQ(monitor.check({0.75, 0.0}, {{0.254 + 1.0, -0.01}, {0.254 + 1.0, 0.01}}).action,
              MonitorAction::kNone);
}

TEST(CollisionMonitor, ALowFootSeenInOneSweepIsRemembered) {
    // A round table's foot (radius 0.28 m, 3 cm high) around a pedestal at x = 1.2 m: the lowest
    // beam (-25 deg from 0.45 m) reaches its top only 0.90-0.965 m from the sensor, so a robot
    // driving at it sees the foot's near edge in one sweep (an arc of returns), then never again.
    const Eigen::Vector2d table(1.2, 0.0);
    auto sweep_from = [&](double x) {
        PointCloud c;
        for (int a = 0; a < 36; ++a) {
            const Eigen::Vector2d p =
                table + 0.05 * Eigen::Vector2d(std::cos(a * kPi / 18), std::sin(a * kPi / 18));
            c.xyz.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.3f);
        }
        for (int a = 0; a < 360; ++a) {
            const Eigen::Vector2d p =
                table + 0.28 * Eigen::Vector2d(std::cos(a * kPi / 180), std::sin(a * kPi / 180));
            const double r = (p - Eigen::Vector2d(x, 0.0)).norm();
            if (r >= 0.90 && r <= 0.965)
                c.xyz.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.03f);
        }
        return c;
    };
    for (const int support : {0, 4}) {
        CollisionMonitorParams p = jackal();
        p.low_edge_support = support;
        CollisionMonitor monitor(p);
        const VelocityCommand ahead{0.5, 0.0};
        for (int k = 0; k <= 4; ++k) {  // the foot's near edge comes into the lowest ring at x = 0
            const double x = -0.2 + 0.05 * k;
            const PointCloud sweep = sweep_from(x);
            monitor.filter({0.1 * k, {x, 0.0, 0.0}, &sweep, ahead, 0.5, 0.0});
        }
        // At x = 0.45 the stop zone (front 0.254 + 0.1 m of latency + 0.125 m of braking + 4 cm)
        // reaches x = 0.97: past the foot's edge (0.92), short of the pedestal (1.15).
        const PointCloud later = sweep_from(0.45);
        const MonitorResult r = monitor.filter({0.6, {0.45, 0.0, 0.0}, &later, ahead, 0.5, 0.0});
        if (support > 0) {
            EXPECT_EQ(r.action, MonitorAction::kStop);
        } else {
            EXPECT_NE(r.action,
                      MonitorAction::kStop);  // a foot seen once is forgotten: driven into
        }
    }
}

TEST(CollisionMonitor, HeldRobotBacksUpIntoFreeSpaceThenTurnsWhenBoxedIn) {
    CollisionMonitorParams p = jackal();
    CollisionMonitor monitor(p);
    const double front = 0.254;
    PointCloud wall;
    for (double y = -1.0; y <= 1.0; y += 0.02)
        wall.xyz.emplace_back(static_cast<float>(front + 0.05), static_cast<float>(y), 0.2f);
    MonitorResult r;
    int t = 0;
    for (; t < 50 && !r.started_recovery; ++t) r = monitor.filter({0.1 * t, {}, &wall, {0.5, 0.0}});
    ASSERT_TRUE(r.started_recovery);
    EXPECT_NEAR(0.1 * (t - 1), p.recovery_after_s, 0.15);
    EXPECT_EQ(r.action, MonitorAction::kBackup);
    EXPECT_LT(r.command.v_mps, 0.0);
    // A table edge just off the left front corner (0.39 m from the centre: the stop zone from a
    // standstill reaches it, a turn on the spot does not: corners at 0.333 m + 4 cm padding) and a
    // wall 0.40 m behind: no room to back up 0.3 m, so it turns on the spot.
    CollisionMonitor boxed(p);
    PointCloud both;
    both.xyz.emplace_back(0.31f, 0.23f, 0.2f);
    both.xyz.emplace_back(0.31f, 0.245f, 0.2f);
    for (double y = -1.0; y <= 1.0; y += 0.02)
        both.xyz.emplace_back(-0.40f, static_cast<float>(y), 0.2f);
    r = {};
    for (t = 0; t < 50 && !r.started_recovery; ++t)
        r = boxed.filter({0.1 * t, {}, &both, {0.5, 0.0}});
    ASSERT_TRUE(r.started_recovery);
    EXPECT_EQ(r.action, MonitorAction::kRotate);
    EXPECT_EQ(r.command.v_mps, 0.0);
    EXPECT_NE(r.command.w_radps, 0.0);
    // Closed in on every side: held, and it says so.
    CollisionMonitor closed(p);
    PointCloud ring;
    for (int k = 0; k < 72; ++k)
        ring.xyz.emplace_back(0.36f * static_cast<float>(std::cos(k * kPi / 36)),
                              0.3f * static_cast<float>(std::sin(k * kPi / 36)), 0.2f);
    bool blocked = false, moved = false;
    for (t = 0; t < 40; ++t) {
        r = closed.filter({0.1 * t, {}, &ring, {0.5, 0.0}});
        blocked |= r.action == MonitorAction::kBlocked;
        moved |= r.command.v_mps != 0.0 || r.command.w_radps != 0.0;
    }
    EXPECT_TRUE(blocked);
    EXPECT_FALSE(moved);
}

TEST(CollisionMonitor, ObjectFootprintsCoverAChairBaseTheSensorCannotSee) {
    // A chair pulled up beside a robot turning on the spot: its base (half 0.30 m, 10 cm up) is
    // inside the blind ring, its seat (half 0.20 m, 0.45 m up) is seen. The base's edge is 3.5 cm
    // from the side of the footprint; the footprint's corners sweep 0.333 m out, into the base.
    const sim::RobotParams robot;
    const Eigen::Vector2d chair(0.0, 0.55);
    const std::vector<Eigen::Vector2d> base = box_outline(chair, {0.3, 0.3}),
                                       seat = box_outline(chair, {0.2, 0.2});
    const std::vector<Polygon2> footprints = {
        {chair + Eigen::Vector2d(-0.3, -0.3), chair + Eigen::Vector2d(0.3, -0.3),
         chair + Eigen::Vector2d(0.3, 0.3), chair + Eigen::Vector2d(-0.3, 0.3)}};
    for (const bool with_footprints : {false, true}) {
        CollisionMonitor monitor(jackal());
        sim::RobotState state;
        VelocityCommand cmd{0.0, 1.0};
        double closest = 1e9;
        for (int k = 0; k < 40; ++k) {
            for (int i = 0; i < 10; ++i) {
                state = sim::step_diff_drive(state, cmd, 0.01, robot);
                for (const auto& p : base)
                    closest = std::min(closest, footprint_distance(state.pose, p));
            }
            const PointCloud sweep = sweep_of(seat, state.pose, 0.0, 0.45f);
            const MonitorResult r = monitor.filter({0.1 * (k + 1),
                                                    state.pose,
                                                    &sweep,
                                                    {0.0, 1.0},
                                                    state.v_mps,
                                                    state.w_radps,
                                                    with_footprints ? &footprints : nullptr});
            cmd = r.command;
        }
        if (with_footprints) {
            EXPECT_GT(closest, 0.0);  // held, or turned away: never into the base
        } else {
            EXPECT_EQ(closest, 0.0);  // the seat alone lets the corner sweep into the base
        }
    }
}

TEST(CollisionMonitor, IgnoresReturnsTheBodyCannotHitAndRejectsBadParams) {
    CollisionMonitor monitor(jackal());
    PointCloud overhead;  // a table top above the robot, and the floor
    for (double y = -0.3; y <= 0.3; y += 0.02) {
        overhead.xyz.emplace_back(0.5f, static_cast<float>(y), 0.72f);
        overhead.xyz.emplace_back(0.5f, static_cast<float>(y), 0.0f);
    }
    EXPECT_EQ(monitor.filter({0.1, {}, &overhead, {0.5, 0.0}}).action, MonitorAction::kNone);
    CollisionMonitorParams bad = jackal();
    bad.slowdown_ratio = 0.0;
    bad.min_points = 0;
    try {
        CollisionMonitor m(bad);
        FAIL() << "accepted bad parameters";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("slowdown_ratio"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("min_points"), std::string::npos);
    }
}

}  // namespace
}  // namespace makeway::planning
