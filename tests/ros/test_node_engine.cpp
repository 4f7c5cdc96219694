// The ROS node's engine without ROS: sweeps pushed faster than it processes them are all processed,
// in order, each output stamped with its sweep's end; odometry arriving after a sweep is waited for;
// a full queue drops the oldest and counts it.
#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>

#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"
#include "ros/node_engine.hpp"

namespace makeway::rosio {
namespace {

std::vector<sim::SimFrame> drive(int frames) {
    sim::SceneGenParams g;
    g.seed = 1000041;
    g.density = sim::Density::kMedium;
    const sim::Scene scene = sim::generate_scene(g);
    const sim::RobotParams robot;
    const auto route = sim::drive_route(scene, sim::CollisionChecker(scene, sim::models_of(scene), robot), robot);
    sim::SequenceSimulator s(scene, route.value_or(std::vector<Eigen::Vector2d>{}), {});
    std::vector<sim::SimFrame> out;
    for (int k = 0; k < frames; ++k) out.push_back(s.next());
    return out;
}

CloudSweep sweep_of(const sim::SimFrame& f) {
    CloudSweep c;
    c.points.xyz = f.points_sensor.xyz;
    c.points.time_s = f.points_sensor.time_s;
    c.stamp_s = 100.0 + f.stamp_s;
    c.duration_s = 0.1;
    c.timed = true;
    return c;
}

NodeSettings settings() {
    NodeSettings s;
    s.model = (std::filesystem::path(MAKEWAY_SOURCE_DIR) / "models" / "detector.pt").string();
    return s;
}

TEST(NodeEngine, EverySweepInOrderStampedWithItsEnd) {
    const auto frames = drive(25);
    std::mutex m;
    std::vector<double> stamps;
    std::size_t keyframes = 0, objects = 0;
    {
        NodeEngine engine(settings(), [&](const NodeOutput& out) {
            std::lock_guard<std::mutex> lock(m);
            stamps.push_back(out.stamp_s);
            keyframes += out.keyframe;
            objects = out.objects.size();
            EXPECT_NE(out.costmap, nullptr);
            if (out.keyframe) {
                EXPECT_NE(out.object_map_json.find("\"objects\""), std::string::npos);
            }
        });
        // All sweeps at once (far faster than 10 Hz), each with its odometry pushed after it: the
        // engine waits for odometry that covers the sweep's end.
        for (const auto& f : frames) {
            engine.push_sweep(sweep_of(f));
            engine.push_odometry({100.0 + f.stamp_s, f.odometry_pose});
            engine.push_odometry({100.0 + f.stamp_s + 0.1, f.odometry_end_pose});
        }
        engine.drain();
        const NodeStats s = engine.stats();
        EXPECT_EQ(s.received, 25u);
        EXPECT_EQ(s.processed, 25u);
        EXPECT_EQ(s.dropped, 0u);
        EXPECT_EQ(s.keyframes, 5u);
        EXPECT_GT(s.max_queue, 1u);  // they did queue up
    }
    ASSERT_EQ(stamps.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_NEAR(stamps[i], 100.0 + frames[i].stamp_s + 0.1, 1e-9);
    EXPECT_EQ(keyframes, 5u);
    EXPECT_GT(objects, 0u);  // the committed detector maps something in a medium scene
}

TEST(NodeEngine, AFullQueueDropsTheOldestAndCountsIt) {
    const auto frames = drive(12);
    NodeSettings s = settings();
    s.max_queue = 2;
    s.odometry_wait_s = 0.0;
    std::vector<double> stamps;
    std::mutex m;
    NodeStats stats;
    {
        NodeEngine engine(s, [&](const NodeOutput& out) {
            std::lock_guard<std::mutex> lock(m);
            stamps.push_back(out.stamp_s);
        });
        for (const auto& f : frames) engine.push_sweep(sweep_of(f));
        engine.drain();
        stats = engine.stats();
    }
    EXPECT_EQ(stats.received, 12u);
    EXPECT_EQ(stats.processed + stats.dropped, 12u);
    EXPECT_GT(stats.dropped, 0u);
    EXPECT_EQ(stamps.size(), stats.processed);
    EXPECT_NEAR(stamps.back(), 100.0 + frames.back().stamp_s + 0.1, 1e-9);  // the newest always survives
    for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_GT(stamps[i], stamps[i - 1]);
}

}  // namespace
}  // namespace makeway::rosio
