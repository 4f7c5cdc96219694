// The chairs the collision monitor gives way to (MovingChairs), with known answers: a chair the
// object map holds at rest while its box steps toward the robot keyframe by keyframe.
#include <gtest/gtest.h>

#include "makeway/pipeline/online_system.hpp"

namespace makeway::pipeline {
namespace {

ObjectEstimate chair_at(double x, double y, std::uint32_t id = 3) {
    ObjectEstimate o;
    o.id = id;
    o.cls = ObjectClass::kChair;
    o.box_world.centre_m = {x, y, 0.45};
    o.box_world.size_m = {0.45, 0.45, 0.9};
    return o;
}

TEST(MovingChairs, ABoxSteppingEveryKeyframeMovesThoughTheMapHoldsItAtRest) {
    MovingChairs movers(0.08, 1.0);
    std::vector<std::size_t> counts;
    planning::MovingOutline last;
    for (int k = 0; k <= 20; ++k) {  // 2 s at 10 Hz; the box steps 6 cm every 0.5 s (0.12 m/s)
        const double t = 0.1 * k;
        const auto out = movers.update(t, {chair_at(2.0, 1.0 - 0.06 * (k / 5))}, 0.5);
        counts.push_back(out.size());
        if (!out.empty()) last = out.front();
    }
    // Nothing before a whole window has passed (1 s); then the displacement over the window.
    for (int k = 0; k < 10; ++k) EXPECT_EQ(counts[k], 0u) << k;
    EXPECT_EQ(counts[10], 1u);
    EXPECT_EQ(counts.back(), 1u);
    EXPECT_NEAR(last.velocity_mps.x(), 0.0, 1e-12);
    EXPECT_NEAR(last.velocity_mps.y(), -0.12, 1e-9);  // 2 steps over the last 1 s
    EXPECT_EQ(last.outline.size(), 4u);               // its box
}

Eigen::Vector2d centre_of(const planning::MovingOutline& m) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& q : m.outline) c += q;
    return c / static_cast<double>(m.outline.size());
}

TEST(MovingChairs, TheBoxIsCarriedToNowFromWhenTheKeyframeMeasuredIt) {
    // The map's box steps 6 cm every keyframe (0.5 s): each box was measured lag_s (0.3 s) before
    // the cycle it first appears in, and the chair moved on at 0.12 m/s since.
    MovingChairs movers(0.08, 1.0, 0.3);
    for (int k = 0; k <= 17; ++k) {
        const double t = 0.1 * k;
        const double box_y = 1.0 - 0.06 * (k / 5);
        const auto out = movers.update(t, {chair_at(2.0, box_y)}, 0.5);
        if (k < 10) continue;  // no velocity before a whole window
        ASSERT_EQ(out.size(), 1u) << k;
        const double since = 0.5 * (k / 5);  // the cycle the box changed in
        const Eigen::Vector2d c = centre_of(out.front());
        EXPECT_NEAR(c.x(), 2.0, 1e-9) << k;
        EXPECT_NEAR(c.y(), box_y - 0.12 * (t - since + 0.3), 1e-9) << k;
    }
    // A box that changes every cycle (the truth, lag 0) is where the chair is now.
    MovingChairs truth(0.08, 1.0, 0.0);
    ObjectEstimate pulled = chair_at(2.0, 1.0);
    pulled.velocity_mps = {0.0, -0.2};
    for (int k = 0; k <= 5; ++k) {
        pulled.box_world.centre_m.y() = 1.0 - 0.02 * k;
        const auto out = truth.update(0.1 * k, {pulled}, 0.5);
        ASSERT_EQ(out.size(), 1u);
        EXPECT_NEAR(centre_of(out.front()).y(), 1.0 - 0.02 * k, 1e-9) << k;
    }
}

TEST(MovingChairs, AStillBoxThatJittersIsNoMover) {
    MovingChairs movers(0.08, 1.0);
    for (int k = 0; k <= 40; ++k) {
        const double jitter = (k / 5) % 2 == 0 ? 0.03 : -0.03;  // +-3 cm keyframe to keyframe
        EXPECT_TRUE(movers.update(0.1 * k, {chair_at(2.0 + jitter, 1.0)}, 0.5).empty()) << k;
    }
}

TEST(MovingChairs, TheMapsVelocityCountsAtOnceAndOnlyChairsThatAreLikely) {
    MovingChairs movers(0.08, 1.0);
    ObjectEstimate pushed = chair_at(2.0, 1.0);
    pushed.velocity_mps = {0.0, -0.2};
    ObjectEstimate unlikely = pushed;
    unlikely.id = 4;
    unlikely.existence = 0.3;
    ObjectEstimate table = pushed;
    table.id = 5;
    table.cls = ObjectClass::kTable;
    const auto out = movers.update(0.0, {pushed, unlikely, table}, 0.5);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out.front().velocity_mps, pushed.velocity_mps);
    // Slower than the threshold, on the map and over the window: not a mover.
    pushed.velocity_mps = {0.0, -0.05};
    EXPECT_TRUE(movers.update(0.1, {pushed}, 0.5).empty());
}

TEST(MovingChairs, AChairTheMapDroppedStartsAfresh) {
    MovingChairs movers(0.08, 1.0);
    movers.update(0.0, {chair_at(2.0, 1.0)}, 0.5);
    // Back 3 s later 0.5 m away (another chair the map gave the same id, or a re-detection):
    // no velocity from the old box.
    for (int k = 0; k < 4; ++k)
        EXPECT_TRUE(movers.update(3.0 + 0.1 * k, {chair_at(2.0, 0.5)}, 0.5).empty()) << k;
}

}  // namespace
}  // namespace makeway::pipeline
