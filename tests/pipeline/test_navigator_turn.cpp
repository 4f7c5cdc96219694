// The navigator's last resort: when DWA finds every velocity colliding it turns on the spot toward
// its plan; with turn_clear_rad that turn is checked against the costmap's lethal cells, which keep
// what the obstacle layer marked from farther away (a chair's leg) where the monitor's latest
// sweep, inside the sensor's blind ring, no longer shows it.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "makeway/pipeline/navigator.hpp"

namespace makeway::pipeline {
namespace {

// A room 6 m wide at 2 cm cells, its border lethal, with lethal cells at `legs` (world).
Costmap room_with(const std::vector<Eigen::Vector2d>& legs) {
    Costmap map({-3.0, -3.0}, 0.02, 300, 300, cost::kFree);
    for (int i = 0; i < 300; ++i) {
        for (int j : {0, 299}) map.at(i, j) = map.at(j, i) = cost::kLethal;
    }
    for (const Eigen::Vector2d& p : legs) {
        const Eigen::Vector2i c = map.cell_of(p);
        map.at(c.x(), c.y()) = cost::kLethal;
    }
    return map;
}

NavigatorStep first_step(const Costmap& map, const NavigatorParams& params) {
    Navigator nav(map, params);
    nav.set_route({{2.5, -0.5}});  // ahead, a little right: A* leads away from a leg
    return nav.step({0.0, {0.0, 0.0, 0.0}, 0.0, 0.0, nullptr, Eigen::Vector3d::Zero(), {}});
}

// A leg 2.5 cm off the robot's left side near its back (outside the bare footprint, inside the
// padded one, so DWA finds nothing), the plan ahead leading a little right of it: the turn toward
// the plan (right) sweeps the rear-left corner over the leg within 0.2 rad, so the robot stands
// (without progress, the stuck recovery backs it up later). A leg beside the front instead,
// which the front-left corner turns away from, lets it turn.
TEST(NavigatorTurn, TurnsOnTheSpotOnlyWhereTheCostmapShowsTheSweepFree) {
    NavigatorParams params;
    params.affordance_layer = false;
    params.turn_clear_rad = 0.5;
    ASSERT_GE(std::max(params.dwa.footprint_padding_m, params.monitor.stop_padding_m), 0.03);
    const Eigen::Vector2d rear_leg(-0.17, 0.245), front_leg(0.15, 0.245);

    const NavigatorStep free_room = first_step(room_with({}), params);
    ASSERT_TRUE(free_room.dwa_found);  // the precondition: only a leg makes DWA give up

    const NavigatorStep unchecked = [&] {
        NavigatorParams p = params;
        p.turn_clear_rad = 0.0;  // the turn as it was: toward the plan, whatever it sweeps
        return first_step(room_with({rear_leg}), p);
    }();
    ASSERT_FALSE(unchecked.dwa_found);
    EXPECT_NEAR(unchecked.command.w_radps, -params.turn_rate_radps, 1e-12);  // into the leg

    const NavigatorStep held = first_step(room_with({rear_leg}), params);
    ASSERT_FALSE(held.dwa_found);
    EXPECT_EQ(held.command.v_mps, 0.0);
    EXPECT_EQ(held.command.w_radps, 0.0);

    const NavigatorStep clear = first_step(room_with({front_leg}), params);
    ASSERT_FALSE(clear.dwa_found);
    EXPECT_EQ(clear.command.v_mps, 0.0);
    EXPECT_NEAR(clear.command.w_radps, -params.turn_rate_radps, 1e-12);

    // A lethal cell the bare footprint already stands on does not hold the turn (a mark under
    // the robot it could not get off otherwise).
    const NavigatorStep standing_on = first_step(room_with({rear_leg, {-0.24, -0.19}}), params);
    ASSERT_TRUE(standing_on.has_plan);
    ASSERT_FALSE(standing_on.dwa_found);
    EXPECT_NEAR(standing_on.command.w_radps, -params.turn_rate_radps, 1e-12);
}

}  // namespace
}  // namespace makeway::pipeline
