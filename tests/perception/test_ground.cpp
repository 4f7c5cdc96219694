#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/perception/ground.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::perception {
namespace {

// A floor 0.45 m below a sensor tilted by `tilt_deg` about x, a smaller table top 0.3 m above the
// floor, a ceiling, and uniform clutter; all with Gaussian noise.
PointCloud synthetic_scan(double tilt_deg, std::uint64_t seed) {
    Rng rng = make_rng(seed);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(deg_to_rad(tilt_deg), Eigen::Vector3d::UnitX()).toRotationMatrix();
    PointCloud c;
    auto add = [&](const Eigen::Vector3d& p_level) {
        c.xyz.push_back((R * (p_level + Eigen::Vector3d(normal(rng, 0, 0.01), normal(rng, 0, 0.01),
                                                        normal(rng, 0, 0.01))))
                            .cast<float>());
    };
    for (int i = 0; i < 6000; ++i) add({uniform(rng, -8, 8), uniform(rng, -8, 8), -0.45});  // floor
    for (int i = 0; i < 1500; ++i)
        add({uniform(rng, 1, 3), uniform(rng, -1, 1), 0.30});  // table top
    for (int i = 0; i < 2000; ++i)
        add({uniform(rng, -6, 6), uniform(rng, -6, 6), 2.35});  // ceiling
    for (int i = 0; i < 2000; ++i)
        add({uniform(rng, -6, 6), uniform(rng, -6, 6), uniform(rng, -0.4, 2.3)});
    return c;
}

TEST(Ground, FoundInTiltedNoisyScans) {
    for (double tilt : {0.0, 4.0, -9.0}) {
        const PointCloud scan = synthetic_scan(tilt, 5);
        const GroundPlaneResult g = fit_ground_plane(scan, {});
        ASSERT_TRUE(g.found) << g.reason;
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(deg_to_rad(tilt), Eigen::Vector3d::UnitX()).toRotationMatrix();
        const Eigen::Vector3d up = R * Eigen::Vector3d::UnitZ();
        EXPECT_LT(rad_to_deg(std::acos(std::min(1.0, g.normal.dot(up)))), 0.5) << tilt;
        EXPECT_NEAR(g.offset, 0.45, 0.01) << tilt;  // the sensor is 0.45 m above it
        EXPECT_GT(g.inliers, 5000u);
        // The floor below a point lies on the plane; below the sensor it is 0.45 m down.
        EXPECT_NEAR(g.height_of({2.0, -1.5, g.floor_z_at(2.0, -1.5)}), 0.0, 1e-12);
        EXPECT_NEAR(g.floor_z_at(0.0, 0.0), -0.45, 0.02) << tilt;
    }
}

TEST(Ground, RemovesGroundAndCeilingKeepsObjects) {
    const PointCloud scan = synthetic_scan(3.0, 6);
    const GroundPlaneResult g = fit_ground_plane(scan, {});
    ASSERT_TRUE(g.found);
    const PointCloud kept =
        remove_ground_and_ceiling(scan, g, {.ground_band_m = 0.08, .ceiling_height_m = 2.2});
    std::size_t table = 0;
    for (const auto& p : kept.xyz) {
        const double h = g.height_of(p.cast<double>());
        EXPECT_GT(h, 0.08);
        EXPECT_LT(h, 2.2);
        table += std::abs(h - 0.75) < 0.05;
    }
    EXPECT_GT(table, 1400u);        // the table top survives
    EXPECT_LT(kept.size(), 3500u);  // floor and ceiling are gone
}

TEST(Ground, BeamsAtTheHorizonDoNotMakeAGround) {
    // Walls close around the sensor, hit by many beams near 0 deg elevation: their returns all lie
    // within a few centimetres of z = 0, more of them than on the floor.
    Rng rng = make_rng(8);
    PointCloud c;
    for (int i = 0; i < 4000; ++i) {
        const double a = uniform(rng, -kPi, kPi);
        const double r = 2.0;
        c.xyz.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                           static_cast<float>(normal(rng, 0.0, 0.015)));
    }
    for (int i = 0; i < 1500; ++i) {
        c.xyz.emplace_back(static_cast<float>(uniform(rng, -1.9, 1.9)),
                           static_cast<float>(uniform(rng, -1.9, 1.9)),
                           static_cast<float>(-0.45 + normal(rng, 0.0, 0.01)));
    }
    const GroundPlaneResult g = fit_ground_plane(c, {});
    ASSERT_TRUE(g.found);
    EXPECT_NEAR(g.offset, 0.45, 0.02);
}

TEST(Ground, NearAWallTheFloorBeatsTheHorizonBandsAndTheFirstRing) {
    // The demo's start: the study space, the robot 1.3 m from a wall. One keyframe of the real
    // VLP-32C pattern has more points within 5 cm of a 13 deg plane (through the floor's first
    // ring and the dense near-horizon bands on the walls) than on the floor itself.
    const sim::Scene scene = sim::generate_scene({.layout = sim::Layout::kStudySpace});
    sim::World world(scene, sim::models_of(scene));
    const Isometry3 T_world_sensor = lift_to_3d(scene.start) * sim::RobotParams{}.T_robot_sensor();
    PointCloud keyframe;
    for (int k = 0; k < 5; ++k)
        keyframe.append(sim::simulate_sweep(
            world, {}, [&](double) { return T_world_sensor; }, 0.1 * k, 0, k));
    std::size_t floor_points = 0;
    for (const auto& p : keyframe.xyz) floor_points += std::abs(p.z() + 0.45f) < 0.05f;

    const GroundPlaneResult by_area = fit_ground_plane(keyframe, {});
    ASSERT_TRUE(by_area.found) << by_area.reason;
    EXPECT_GT(by_area.normal.z(), std::cos(deg_to_rad(0.5)));
    EXPECT_NEAR(by_area.floor_z_at(0.0, 0.0), -0.45, 0.01);
    const GroundPlaneResult by_points = fit_ground_plane(keyframe, {.voxel_m = 0.0});
    EXPECT_GT(by_points.inliers, floor_points);  // the trap this test is about is there
    EXPECT_LT(by_points.normal.z(), std::cos(deg_to_rad(5.0)));
}

TEST(Ground, ClearResultWhenThereIsNoPlane) {
    PointCloud wall;
    Rng rng = make_rng(2);
    for (int i = 0; i < 1000; ++i)
        wall.xyz.emplace_back(3.0f, static_cast<float>(uniform(rng, -2, 2)),
                              static_cast<float>(uniform(rng, -1, 1)));
    const GroundPlaneResult g = fit_ground_plane(wall, {});
    EXPECT_FALSE(g.found);
    EXPECT_NE(g.reason.find("no plane"), std::string::npos);
    EXPECT_FALSE(fit_ground_plane(PointCloud{}, {}).found);
    EXPECT_EQ(remove_ground_and_ceiling(wall, g, {}).size(),
              wall.size());  // nothing known: nothing removed
}

}  // namespace
}  // namespace makeway::perception
