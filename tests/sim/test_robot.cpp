#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/sim/contact_judge.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/route.hpp"
#include "sim_test_util.hpp"

namespace makeway::sim {
namespace {

TEST(DiffDrive, RespectsLimitsAndFollowsArcs) {
    RobotParams p;
    RobotState s;
    s = step_diff_drive(s, {5.0, 0.0}, 0.1, p);
    EXPECT_NEAR(s.v_mps, 0.1, 1e-12);  // 1 m/s^2 for 0.1 s
    for (int i = 0; i < 100; ++i) s = step_diff_drive(s, {5.0, 0.0}, 0.1, p);
    EXPECT_NEAR(s.v_mps, 0.75, 1e-12);  // top speed
    EXPECT_NEAR(s.pose.y_m, 0.0, 1e-12);
    // A full circle at constant speeds returns to its start.
    RobotState c;
    c.v_mps = 0.5;
    c.w_radps = 0.5;
    for (int i = 0; i < 1000; ++i) c = step_diff_drive(c, {0.5, 0.5}, 2 * kPi / 0.5 / 1000, p);
    EXPECT_NEAR(c.pose.x_m, 0.0, 1e-9);
    EXPECT_NEAR(c.pose.y_m, 0.0, 1e-9);
}

TEST(WheelOdometry, ExactWithoutNoiseAndDriftsWithIt) {
    RobotParams p;
    RobotState s;
    WheelOdometry exact({}, {0.0, 0.0, 0.0}, 1), noisy({}, {}, 1);
    for (int i = 0; i < 2000; ++i) {
        const RobotState before = s;
        s = step_diff_drive(s, {0.6, 0.2 * std::sin(i * 0.01)}, 0.01, p);
        exact.update(before.pose, s.pose);
        noisy.update(before.pose, s.pose);
    }
    EXPECT_NEAR(exact.pose().x_m, s.pose.x_m, 1e-9);
    EXPECT_NEAR(exact.pose().yaw_rad, s.pose.yaw_rad, 1e-9);
    const double err = std::hypot(noisy.pose().x_m - s.pose.x_m, noisy.pose().y_m - s.pose.y_m);
    EXPECT_GT(err, 1e-4);
    EXPECT_LT(err, 1.0);  // about 11 m driven
}

TEST(Collision, FootprintAgainstWallsAndFurniture) {
    Scene s = testing_util::box_room(3.0);
    SceneObject table;
    table.id = 1;
    table.cls = ObjectClass::kTable;
    table.style = "rect_table";
    table.pose = {0.0, 0.0, 0.0};
    s.objects.push_back(table);
    const std::vector<ObjectModel> models{model_of(table)};
    const RobotParams robot;
    const CollisionChecker checker(s, models, robot);
    EXPECT_TRUE(checker.collides({2.9, 0.0, 0.0}, 0.0));  // through the wall
    EXPECT_FALSE(checker.collides({2.0, 2.0, 0.0}, 0.0));
    const double half_l = 0.5 * models[0].box_object.size_m.x();
    EXPECT_TRUE(checker.collides({half_l, 0.3, 0.0}, 0.0));  // on a leg corner region
    EXPECT_FALSE(checker.collides({0.0, 0.0, 0.0}, 0.0));    // under the table top, between legs
    const double c1 = checker.clearance_m({1.8, 1.8, 0.0}, 0.0);
    const double c2 = checker.clearance_m({2.2, 2.2, 0.0}, 0.0);
    EXPECT_GT(c1, c2);
    EXPECT_NEAR(checker.clearance_m({0.0, 2.0, 0.0}, 0.0), 3.0 - 2.0 - 0.215, 0.03);
}

TEST(Route, AStarOnAHandDrawnGrid) {
    NavGrid g;
    g.width = 10;
    g.height = 5;
    g.resolution_m = 1.0;
    g.blocked.assign(50, 0);
    for (int y = 0; y < 4; ++y) g.blocked[y * 10 + 5] = 1;  // a wall with a gap at the top
    const auto r = find_route(g, {0.5, 0.5}, {9.5, 0.5});
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->front().x(), 0.5, 1e-12);
    EXPECT_NEAR(r->back().x(), 9.5, 1e-12);
    // It must pass through the gap, cell (5, 4): at least 2 * hypot(4.5, 3.5) long.
    EXPECT_GT(route_length_m(*r), 2 * std::hypot(4.5, 3.5));
    EXPECT_LT(route_length_m(*r), 13.0);
    g.blocked[4 * 10 + 5] = 1;
    EXPECT_FALSE(find_route(g, {0.5, 0.5}, {9.5, 0.5}).has_value());
    EXPECT_FALSE(find_route(g, {5.5, 0.5}, {9.5, 0.5}).has_value());  // start blocked
}

// The one judge of the benchmark and the ROS sim node, on contacts built by hand: the robot
// driving into a wall (its doing, counted once while it touches, again after it backed off), and
// a walker walking into the robot standing still (another's doing).
TEST(ContactJudge, CountsEachContactOnceByKindAndCause) {
    Scene room = testing_util::box_room(2.0);  // inner faces at +-2 m
    room.walkers.push_back({{{-1.8, -1.0}, {1.8, -1.0}}, 0.8, 0.0});
    const RobotParams robot;
    const std::vector<ObjectModel> models;
    const CollisionChecker checker(room, models, robot);
    ContactJudge judge(checker, robot);
    std::vector<ContactEvent> events;
    RobotState s;
    s.pose = {1.0, 1.0, 0.0};
    s.v_mps = 0.5;
    double t = 100.0;                           // the walker is elsewhere (it passes y = -1 only)
    for (int k = 0; k < 100; ++k, t += 0.02) {  // drives on into the wall, 2 cm a step
        s.pose.x_m = 1.0 + 0.01 * k;
        for (ContactEvent& e : judge.step(s, t)) events.push_back(e);
    }
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, "walls");
    EXPECT_TRUE(events[0].robot_caused);
    EXPECT_NEAR(events[0].toward_mps, 0.5, 1e-9);
    EXPECT_NEAR(s.pose.x_m, 1.99, 1e-9);
    EXPECT_NEAR(events[0].where_m.x(), 2.0, 0.05);
    s.pose.x_m = 1.0;  // backed off ...
    EXPECT_TRUE(judge.step(s, t).empty());
    s.pose.x_m = 1.9;  // ... and into it again
    ASSERT_EQ(judge.step(s, t).size(), 1u);
    // Standing still on the walker's line: the walker walks into it.
    ContactJudge still(checker, robot);
    RobotState stopped;
    stopped.pose = {0.0, -1.0, kPi / 2};
    std::vector<ContactEvent> people;
    for (double tw = 0.0; tw < 4.5; tw += 0.02) {
        for (ContactEvent& e : still.step(stopped, tw)) people.push_back(e);
    }
    ASSERT_EQ(people.size(), 1u);
    EXPECT_EQ(people[0].kind, "people");
    EXPECT_FALSE(people[0].robot_caused);
}

}  // namespace
}  // namespace makeway::sim
