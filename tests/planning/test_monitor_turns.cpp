// The collision monitor's turn cap beside walkers (dynamic_turn_space_m): a turning robot's corners
// sweep sideways at w times their reach from the centre, into a walker beside them even while the
// body as a whole moves away from the walker, which the zones (made for what the robot closes in
// on) let through. Known answers on single checks, and closed loops on the simulator's drive model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "makeway/common/angles.hpp"
#include "makeway/planning/collision_monitor.hpp"
#include "makeway/sim/robot.hpp"
#include "monitor_test_util.hpp"

namespace makeway::planning {
namespace {

// A walker's returns 5 cm behind the right rear corner (base frame: x forward, y left).
std::vector<Eigen::Vector2d> walker_behind_right_corner() {
    std::vector<Eigen::Vector2d> out;
    for (double a = 0.0; a < 2.0 * kPi; a += kPi / 18)
        out.emplace_back(-0.254 - 0.05 - 0.2 + 0.2 * std::cos(a), -0.215 + 0.2 * std::sin(a));
    return out;
}

TEST(MonitorTurnCap, SlowsATurnBesideAWalkerOnly) {
    const std::vector<Eigen::Vector2d> walker = walker_behind_right_corner();
    const VelocityCommand drive_off{0.6, 0.5};  // forward and left: the rear swings right
    CollisionMonitorParams p = jackal();
    p.dynamic_turn_space_m = 0.0;
    // Off: driving away from the walker is what the zones let through, as it is.
    const MonitorResult off = CollisionMonitor(p).check(drive_off, drive_off, walker,
                                                        std::vector<char>(walker.size(), 1));
    EXPECT_EQ(off.action, MonitorAction::kNone);
    EXPECT_EQ(off.command.w_radps, 0.5);

    p.dynamic_turn_space_m = 0.3;
    p.dynamic_turn_max_radps = 0.12;
    const CollisionMonitor capped(p);
    const MonitorResult r =
        capped.check(drive_off, drive_off, walker, std::vector<char>(walker.size(), 1));
    EXPECT_EQ(r.action, MonitorAction::kSlowdown);
    EXPECT_DOUBLE_EQ(r.command.v_mps, 0.6);  // the speed away from it is kept
    EXPECT_DOUBLE_EQ(r.command.w_radps, 0.12);
    const VelocityCommand right{0.6, -0.5};
    EXPECT_DOUBLE_EQ(
        capped.check(right, right, walker, std::vector<char>(walker.size(), 1)).command.w_radps,
        -0.12);
    // Standing returns (a wall's corner), a chair being pulled (2: new beside a known chair), a
    // walker farther than the space, and a turn already that slow are left alone.
    EXPECT_EQ(capped.check(drive_off, drive_off, walker, std::vector<char>(walker.size(), 0))
                  .command.w_radps,
              0.5);
    EXPECT_EQ(capped.check(drive_off, drive_off, walker, std::vector<char>(walker.size(), 2))
                  .command.w_radps,
              0.5);
    std::vector<Eigen::Vector2d> far = walker;
    for (Eigen::Vector2d& q : far) q.x() -= 0.3;
    EXPECT_EQ(
        capped.check(drive_off, drive_off, far, std::vector<char>(far.size(), 1)).command.w_radps,
        0.5);
    const VelocityCommand slow{0.6, 0.1};
    EXPECT_EQ(capped.check(slow, slow, walker, std::vector<char>(walker.size(), 1)).action,
              MonitorAction::kNone);

    p.dynamic_turn_space_m = -0.1;
    EXPECT_FALSE(p.validate().empty());
    p.dynamic_turn_space_m = 0.3;
    p.dynamic_turn_max_radps = 0.0;
    EXPECT_FALSE(p.validate().empty());
}

// Through filter(): returns new in this sweep behind the right rear corner cap the turn, unless
// they lie beside a chair the robot knows of (someone pulling it), with the personal space and the
// movers' memory off (the chair test runs for the turn cap alone).
TEST(MonitorTurnCap, LeavesAPulledChairToTheZones) {
    const std::vector<Eigen::Vector2d> walker = walker_behind_right_corner();
    const PointCloud before = wall_ahead_and(), now = wall_ahead_and(walker);
    const VelocityCommand drive_off{0.6, 0.5};
    const std::vector<Polygon2> pulled = {{{-0.9, -0.1}, {-0.5, -0.1}, {-0.5, -0.5}, {-0.9, -0.5}}};
    const auto turn = [&](const std::vector<Polygon2>* chairs) {
        CollisionMonitorParams p = jackal();
        p.dynamic_personal_space_m = 0.0;  // the defaults, said here: the turn cap alone
        p.dynamic_memory_s = 0.0;
        CollisionMonitor m(p);
        m.filter({0.0, Pose2{}, &before, drive_off, 0.6, 0.5, nullptr, chairs});
        return m.filter({0.1, Pose2{}, &now, drive_off, 0.6, 0.5, nullptr, chairs}).command.w_radps;
    };
    EXPECT_DOUBLE_EQ(turn(nullptr), 0.12);  // a walker: slowed
    EXPECT_DOUBLE_EQ(turn(&pulled), 0.5);   // the chair being pulled: left to the zones
}

// A walker overtakes the robot (walkers here never give way) on a line beside it while the
// navigator turns the robot off that line, at full speed: the rear corner swings into the walker.
// Returns the robot's speed toward the walker when they touch (robot-caused above 0.05 m/s);
// nothing when they never do.
std::optional<double> speed_when_overtaken(double gap_m, double offset_m, double walker_mps,
                                           double w_radps, double space_m) {
    const sim::RobotParams robot;
    CollisionMonitorParams p = jackal();
    p.dynamic_turn_space_m = space_m;
    CollisionMonitor monitor(p);
    sim::RobotState state;
    state.v_mps = 0.6;
    const VelocityCommand asked{0.6, w_radps};
    VelocityCommand cmd{0.6, 0.0};  // straight on until the first check
    const double radius = 0.2;
    const double start = -0.5 * robot.length_m - gap_m - radius;  // gap_m behind the rear
    auto walker_at = [&](double t) { return Eigen::Vector2d(start + walker_mps * t, offset_m); };
    for (int k = 0; k < 40; ++k) {
        const double t = 0.1 * k;
        for (int i = 0; i < 10; ++i) {  // the last command acts for one period
            state = sim::step_diff_drive(state, cmd, 0.01, robot);
            if (const auto toward =
                    speed_toward_walker(state, walker_at(t + 0.01 * (i + 1)), radius))
                return toward;
        }
        const PointCloud sweep = walker_sweep(walker_at(t + 0.1), radius, state.pose);
        cmd = monitor.filter({t + 0.1, state.pose, &sweep, asked, state.v_mps, state.w_radps})
                  .command;
    }
    return std::nullopt;
}

// 288 overtakings (the walker 5-30 cm behind the rear, on a line whose near side runs from 3.5 cm
// inside the robot's side to 2.5 cm outside it, either side, at 1.0-1.4 m/s; the navigator turning
// away from it at 0.3-1.0 rad/s): robot-caused contacts without and with the turn cap.
TEST(MonitorTurnCap, AWalkerOvertakingATurningRobotMeetsNoSwingingCorner) {
    int without = 0, with = 0, touched = 0;
    for (const double side : {-1.0, 1.0}) {
        for (const double gap : {0.05, 0.15, 0.3}) {
            for (const double offset : {0.38, 0.40, 0.42, 0.44}) {
                for (const double speed : {1.0, 1.2, 1.4}) {
                    for (const double w : {0.3, 0.5, 0.8, 1.0}) {
                        // Turning away from the walker's side: the rear swings toward it.
                        const auto off =
                            speed_when_overtaken(gap, side * offset, speed, -side * w, 0.0);
                        const auto on =
                            speed_when_overtaken(gap, side * offset, speed, -side * w, 0.3);
                        touched += off.has_value();
                        without += off.value_or(0.0) > 0.05;
                        with += on.value_or(0.0) > 0.05;
                    }
                }
            }
        }
    }
    std::printf("overtakings: touched %d, robot-caused contacts without the turn cap %d, with %d\n",
                touched, without, with);
    EXPECT_GE(without, 20);  // measured: 32 of 142 contacts
    EXPECT_EQ(with, 0);
}

}  // namespace
}  // namespace makeway::planning
