// The ROS node's engine without ROS: sweeps pushed faster than it processes them are all processed,
// in order, each output stamped with its sweep's end; odometry arriving after a sweep is waited
// for; a full queue drops the oldest and counts it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>

#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/nav_config.hpp"
#include "makeway/eval/navigation.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"
#include "ros/node_engine.hpp"
#include "ros/node_engine_params.hpp"

namespace makeway::rosio {
namespace {

std::vector<sim::SimFrame> drive(int frames, sim::BeamPattern beams = sim::BeamPattern::kVlp32c) {
    sim::SceneGenParams g;
    g.seed = 1000041;
    g.density = sim::Density::kMedium;
    const sim::Scene scene = sim::generate_scene(g);
    const sim::RobotParams robot;
    const auto route =
        sim::drive_route(scene, sim::CollisionChecker(scene, sim::models_of(scene), robot), robot);
    sim::SequenceParams params;
    params.lidar.beam_pattern = beams;
    sim::SequenceSimulator s(scene, route.value_or(std::vector<Eigen::Vector2d>{}), params);
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

// A node started with weights that are not there names the file once, as every makeway command
// does.
TEST(NodeEngine, MissingWeightsAreNamedOnce) {
    NodeSettings s = settings();
    s.model = (std::filesystem::path(::testing::TempDir()) / "no_such_detector.pt").string();
    try {
        NodeEngine engine(s, [](const NodeOutput&) {});
        ADD_FAILURE() << "the engine started without weights";
    } catch (const io::FileError& e) {
        EXPECT_EQ(std::string(e.what()), s.model + ": no such model file");
    }
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
    for (std::size_t i = 0; i < frames.size(); ++i)
        EXPECT_NEAR(stamps[i], 100.0 + frames[i].stamp_s + 0.1, 1e-9);
    EXPECT_EQ(keyframes, 5u);
    EXPECT_GT(objects, 0u);  // the committed detector maps something in a medium scene
}

// The first sweep shows the sensor's lowest beam: a VLP-16 on a robot whose configuration keeps
// the VLP-32C's -25 deg gets its monitor raised to -15 and one notice on the first output; the
// VLP-32C itself gets none.
TEST(NodeEngine, TheFirstSweepSetsTheMonitorToTheSensorsLowestBeam) {
    for (const sim::BeamPattern beams : {sim::BeamPattern::kVlp16, sim::BeamPattern::kVlp32c}) {
        const auto frames = drive(2, beams);
        std::vector<std::string> notices;
        {
            NodeEngine engine(settings(),
                              [&](const NodeOutput& out) { notices.push_back(out.notice); });
            for (const auto& f : frames) {
                engine.push_sweep(sweep_of(f));
                engine.push_odometry({100.0 + f.stamp_s, f.odometry_pose});
                engine.push_odometry({100.0 + f.stamp_s + 0.1, f.odometry_end_pose});
            }
            engine.drain();
        }
        ASSERT_EQ(notices.size(), 2u);
        if (beams == sim::BeamPattern::kVlp16) {
            EXPECT_NE(notices[0].find("lowest beam is at -15.0 deg"), std::string::npos)
                << notices[0];
        } else {
            EXPECT_EQ(notices[0], "");
        }
        EXPECT_EQ(notices[1], "");  // said once
    }
}

// Async perception: every sweep's output comes without waiting for its keyframe; every keyframe
// is still perceived, in order, and its object map published; drain() waits for both.
TEST(NodeEngine, AsyncPerceptionPerceivesEveryKeyframeOffTheControlPath) {
    const auto frames = drive(25);
    NodeSettings s = settings();
    s.async_perception = true;
    std::mutex m;
    std::vector<double> sweep_stamps, keyframe_stamps;
    std::size_t formed = 0, objects = 0;
    {
        NodeEngine engine(s, [&](const NodeOutput& out) {
            std::lock_guard<std::mutex> lock(m);
            if (out.perception) {
                keyframe_stamps.push_back(out.stamp_s);
                objects = out.objects.size();
                EXPECT_EQ(out.costmap, nullptr);
                EXPECT_NE(out.object_map_json.find("\"objects\""), std::string::npos);
                return;
            }
            sweep_stamps.push_back(out.stamp_s);
            formed += out.keyframe;
            EXPECT_NE(out.costmap, nullptr);
            EXPECT_TRUE(out.object_map_json.empty());  // the sweep did not wait for perception
        });
        for (const auto& f : frames) {
            engine.push_sweep(sweep_of(f));
            engine.push_odometry({100.0 + f.stamp_s, f.odometry_pose});
            engine.push_odometry({100.0 + f.stamp_s + 0.1, f.odometry_end_pose});
        }
        engine.drain();
        EXPECT_EQ(engine.stats().keyframes, 5u);
    }
    EXPECT_EQ(sweep_stamps.size(), frames.size());
    EXPECT_EQ(formed, 5u);
    ASSERT_EQ(keyframe_stamps.size(), 5u);
    for (std::size_t i = 1; i < keyframe_stamps.size(); ++i)
        EXPECT_GT(keyframe_stamps[i], keyframe_stamps[i - 1]);  // in order
    EXPECT_GT(objects, 0u);
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
    EXPECT_NEAR(stamps.back(), 100.0 + frames.back().stamp_s + 0.1,
                1e-9);  // the newest always survives
    for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_GT(stamps[i], stamps[i - 1]);
}

TEST(NodeEngine, GateGivesZeroWhenTheSweepsOrTheOdometryStopAndSaysWhy) {
    const VelocityCommand go{0.5, 0.2};
    EXPECT_EQ(gate_command(go, 10.0, 10.05, 10.1, 0.3, 0.3).command.v_mps, 0.5);
    EXPECT_TRUE(gate_command(go, 10.0, 10.05, 10.1, 0.3, 0.3).why.empty());
    const GatedCommand no_sweep = gate_command(go, 10.0, 10.35, 10.31, 0.3, 0.3);
    EXPECT_EQ(no_sweep.command.v_mps, 0.0);
    EXPECT_EQ(no_sweep.command.w_radps, 0.0);
    EXPECT_NE(no_sweep.why.find("no sweep"), std::string::npos);
    const GatedCommand no_odometry = gate_command(go, 10.3, 10.0, 10.31, 0.3, 0.3);
    EXPECT_EQ(no_odometry.command.v_mps, 0.0);
    EXPECT_NE(no_odometry.why.find("no odometry"), std::string::npos);
    EXPECT_EQ(gate_command(go, std::nullopt, 10.0, 10.0, 0.3, 0.3).command.v_mps,
              0.0);  // nothing yet
}

// The benchmark's `ours`, `makeway run` and the node build the online system from one YAML with
// one function (io::online_system_params): a robot and a monitor unlike the defaults reach every
// stage the same way on all three paths.
TEST(OnlineSystem, TheBenchmarkRunAndTheNodeBuildTheSameSystemFromOneYaml) {
    const auto dir = std::filesystem::temp_directory_path() / "makeway_test_three_paths";
    std::filesystem::create_directories(dir);
    const auto yaml = dir / "robot.yaml";
    {
        std::ofstream out(yaml);
        out << "robot: {length_m: 0.7, width_m: 0.5, body_height_m: 0.8, ground_clearance_m: 0.03, "
               "lidar_height_m: 0.7,\n"
               "        max_v_mps: 0.5, max_w_radps: 1.5, max_acc_mps2: 0.8, max_ang_acc_radps2: "
               "2.0}\n"
               "collision_monitor: {stop_padding_m: 0.06, latency_s: 0.25}\n";
    }
    NodeSettings node;
    node.config = yaml.string();
    const pipeline::SystemParams from_node = node_system_params(node);
    const io::Config config = io::load_config(yaml);  // what `makeway run` reads (no simulator)
    const pipeline::SystemParams from_run =
        io::online_system_params(config);  // cmd_run without --extrinsics
    const eval::NavParams nav =
        io::nav_params(io::load_sim_config(yaml));  // the benchmark's reader
    const sim::Scene scene = sim::generate_scene({});
    const pipeline::OnlineSystemSetup from_bench =
        eval::online_system_setup(scene, *eval::nav_method("ours", nav.robot), nav);

    for (const pipeline::SystemParams* p : {&from_node, &from_run, &from_bench.params}) {
        const pipeline::NavigatorParams& n = p->navigator;
        EXPECT_NEAR(p->T_base_sensor.translation().z(), 0.7, 1e-12);
        EXPECT_DOUBLE_EQ(n.dwa.footprint_length_m, 0.7);
        EXPECT_DOUBLE_EQ(n.dwa.footprint_width_m, 0.5);
        EXPECT_DOUBLE_EQ(n.dwa.max_v_mps, 0.5);  // DWA never plans faster than the robot goes
        EXPECT_DOUBLE_EQ(n.dwa.max_w_radps, 1.5);
        EXPECT_DOUBLE_EQ(n.dwa.acc_v_mps2, 0.8);
        EXPECT_DOUBLE_EQ(n.obstacle.body.ground_clearance_m, 0.03);
        EXPECT_DOUBLE_EQ(n.obstacle.body.top_m, 0.8);
        EXPECT_DOUBLE_EQ(n.inflation.inscribed_radius_m, 0.25);
        EXPECT_DOUBLE_EQ(n.inflation.inflation_radius_m, 0.5 * std::hypot(0.7, 0.5));
        EXPECT_TRUE(n.affordance_layer);
        EXPECT_DOUBLE_EQ(n.monitor.footprint_length_m, 0.7);
        EXPECT_DOUBLE_EQ(n.monitor.body.top_m, 0.8);
        EXPECT_DOUBLE_EQ(n.monitor.max_acc_mps2, 0.8);
        EXPECT_DOUBLE_EQ(n.monitor.sensor_height_m, 0.7);  // the blind ring is the mounted sensor's
        EXPECT_DOUBLE_EQ(n.monitor.stop_padding_m, 0.06);
        EXPECT_DOUBLE_EQ(n.monitor.latency_s, 0.25);
    }
    // Measured extrinsics move the monitor's blind ring with the sensor, on the node and in run.
    node.T_base_sensor = make_T_xyz_rpy({0.1, 0.0, 0.55}, 0.0, 0.0, 0.0);
    const Isometry3 T = *node.T_base_sensor;
    EXPECT_DOUBLE_EQ(node_system_params(node).navigator.monitor.sensor_height_m, 0.55);
    EXPECT_DOUBLE_EQ(io::online_system_params(config, &T).navigator.monitor.sensor_height_m, 0.55);
    EXPECT_TRUE(node_system_params(node).T_base_sensor.isApprox(T));
}

// The simulated robot carries the simulated LiDAR: its collision monitor never assumes a lower beam
// than that sensor has (a VLP-16's -15 deg, not the default -25 of a VLP-32C); a more cautious
// value of the file stays.
TEST(OnlineSystem, TheSimulatedRobotsMonitorKnowsItsLidarsLowestBeam) {
    const auto dir = std::filesystem::temp_directory_path() / "makeway_test_lowest_beam";
    std::filesystem::create_directories(dir);
    const auto lowest = [&](const std::string& text) {
        std::ofstream(dir / "c.yaml") << text;
        return io::nav_params(io::load_sim_config(dir / "c.yaml"))
            .system.navigator.monitor.lowest_beam_deg;
    };
    EXPECT_DOUBLE_EQ(lowest("lidar: {beam_pattern: vlp32c}\n"), -25.0);
    EXPECT_DOUBLE_EQ(lowest("lidar: {beam_pattern: vlp16}\n"), -15.0);
    EXPECT_DOUBLE_EQ(lowest("lidar: {beam_pattern: os1_128}\n"), -22.5);
    EXPECT_DOUBLE_EQ(
        lowest("lidar: {beam_pattern: vlp16}\ncollision_monitor: {lowest_beam_deg: -10}\n"), -10.0);
}

}  // namespace
}  // namespace makeway::rosio
