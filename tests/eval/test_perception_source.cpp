#include <gtest/gtest.h>

#include "makeway/eval/perception_source.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
namespace {

TEST(PerceptionObjects, MakesAKeyframeEveryFifthSweepOnceTheWindowIsFull) {
    sim::SceneGenParams g;
    g.seed = 4;
    g.people = false;
    const sim::Scene scene = sim::generate_scene(g);
    const auto models = sim::models_of(scene);
    sim::World world(scene, models);
    perception::DetectorParams dp;
    dp.width = 8;
    const perception::Detector untrained(dp);  // fresh heatmaps peak at 0.1: no detections
    PerceptionObjects source(untrained, nullptr);
    const Isometry3 T_world_sensor = lift_to_3d(scene.start, 0.45);
    std::vector<std::size_t> keyframes;
    for (int k = 0; k < 12; ++k) {
        const PointCloud sweep = sim::simulate_sweep(world, {}, [&](double) { return T_world_sensor; }, 0.1 * k, 1, k);
        EXPECT_TRUE(source.objects({0.1 * k, T_world_sensor, &sweep}).empty());
        keyframes.push_back(source.keyframes());
    }
    // The window fills at the 5th sweep (a keyframe), then one every 5 sweeps: sweeps 5 and 10.
    EXPECT_EQ(keyframes[3], 0u);
    EXPECT_EQ(keyframes[4], 1u);
    EXPECT_EQ(keyframes[8], 1u);
    EXPECT_EQ(keyframes[9], 2u);
    EXPECT_EQ(keyframes[11], 2u);
    EXPECT_TRUE(source.objects({2.0, T_world_sensor, nullptr}).empty());  // no sweep: the last map
}

}  // namespace
}  // namespace makeway::eval
