// The lowest beam a sweep shows, and the monitor's setting raised to it (planning/beam_check.hpp):
// simulated sweeps of a closed room by sensors of known beams.
#include <gtest/gtest.h>

#include "makeway/planning/beam_check.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/mesh_primitives.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::planning {
namespace {

PointCloud sweep_of(sim::BeamPattern pattern) {
    sim::Scene room;
    room.floor_min_m = {-5, -5};
    room.floor_max_m = {5, 5};
    room.walls = {{{-5, -5}, {5, -5}}, {{5, -5}, {5, 5}}, {{5, 5}, {-5, 5}}, {{-5, 5}, {-5, -5}}};
    sim::World world(room, {});
    sim::LidarParams lidar;
    lidar.beam_pattern = pattern;
    return sim::simulate_sweep(
        world, lidar,
        [](double) {
            return make_T_xyz_yaw({0.5, -0.3, 0.45}, 0.2);
        },
        0.0, 7, 0);
}

TEST(BeamCheck, ASweepShowsItsSensorsLowestBeam) {
    EXPECT_NEAR(*lowest_beam_seen_deg(sweep_of(sim::BeamPattern::kVlp16)), -15.0, 0.05);
    EXPECT_NEAR(*lowest_beam_seen_deg(sweep_of(sim::BeamPattern::kVlp32c)), -25.0, 0.05);
    EXPECT_NEAR(*lowest_beam_seen_deg(sweep_of(sim::BeamPattern::kOs1_128)), -22.5, 0.05);
    EXPECT_FALSE(lowest_beam_seen_deg(PointCloud{}));  // nothing to judge by
}

TEST(BeamCheck, TheMonitorIsRaisedToTheSensorNeverLowered) {
    const PointCloud vlp16 = sweep_of(sim::BeamPattern::kVlp16);
    CollisionMonitorParams m;  // -25: a VLP-32C's
    const std::string notice = raise_lowest_beam(m, vlp16);
    EXPECT_NEAR(m.lowest_beam_deg, -15.0, 0.05);
    EXPECT_NE(notice.find("collision_monitor.lowest_beam_deg is -25.0"), std::string::npos)
        << notice;
    // Set for the sensor, or more cautious: left alone, nothing said.
    m.lowest_beam_deg = -15.0;
    EXPECT_EQ(raise_lowest_beam(m, vlp16), "");
    m.lowest_beam_deg = -10.0;
    EXPECT_EQ(raise_lowest_beam(m, vlp16), "");
    EXPECT_DOUBLE_EQ(m.lowest_beam_deg, -10.0);
    // A VLP-32C under the default: nothing to raise.
    CollisionMonitorParams d;
    EXPECT_EQ(raise_lowest_beam(d, sweep_of(sim::BeamPattern::kVlp32c)), "");
    EXPECT_DOUBLE_EQ(d.lowest_beam_deg, -25.0);
}

}  // namespace
}  // namespace makeway::planning
