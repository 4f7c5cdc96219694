#include <gtest/gtest.h>

#include <cmath>

#include <fstream>

#include "io/sim_config.hpp"
#include "io/error.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

std::string problem_of(const std::string& yaml) {
    try {
        parse_sim_config(yaml);
    } catch (const FormatError& e) {
        return e.what();
    }
    return "";
}

TEST(Config, ShippedDefaultFileMatchesBuiltInDefaults) {
    const SimConfig c = load_sim_config(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml");
    const SimConfig d;
    EXPECT_EQ(c.scene.seed, d.scene.seed);
    EXPECT_EQ(c.scene.density, d.scene.density);
    EXPECT_EQ(c.scene.layout, d.scene.layout);
    EXPECT_EQ(c.scene.people, d.scene.people);
    EXPECT_EQ(c.lidar.azimuth_step_deg, d.lidar.azimuth_step_deg);
    EXPECT_EQ(c.lidar.range_noise_m, d.lidar.range_noise_m);
    EXPECT_EQ(c.lidar.dropout, d.lidar.dropout);
    EXPECT_EQ(c.lidar.max_range_m, d.lidar.max_range_m);
    EXPECT_EQ(c.robot.length_m, d.robot.length_m);
    EXPECT_EQ(c.robot.width_m, d.robot.width_m);
    EXPECT_EQ(c.robot.lidar_height_m, d.robot.lidar_height_m);
    EXPECT_EQ(c.robot.max_v_mps, d.robot.max_v_mps);
    EXPECT_EQ(c.odometry.translation_noise_per_m, d.odometry.translation_noise_per_m);
    EXPECT_EQ(c.odometry.heading_noise_per_m, d.odometry.heading_noise_per_m);
    EXPECT_EQ(c.simulation.frames, d.simulation.frames);
    EXPECT_EQ(c.affordance.chair.forward_back_m, d.affordance.chair.forward_back_m);
    EXPECT_EQ(c.affordance.chair.peak_cost, d.affordance.chair.peak_cost);
    EXPECT_EQ(c.affordance.table.sides_m, d.affordance.table.sides_m);
    EXPECT_EQ(c.affordance.table.ends_m, d.affordance.table.ends_m);
    EXPECT_EQ(c.affordance.min_existence, d.affordance.min_existence);
    EXPECT_EQ(c.system.verify.shape_e_max_m, d.system.verify.shape_e_max_m);
    EXPECT_EQ(c.system.shapes.match_distance_m, d.system.shapes.match_distance_m);
    EXPECT_EQ(c.system.shapes.max_views, d.system.shapes.max_views);
    EXPECT_EQ(c.system.shapes.view_margin_m, d.system.shapes.view_margin_m);
    const auto& ct = c.system.tracker;
    const auto& dt = d.system.tracker;
    EXPECT_EQ(ct.tracked_classes, dt.tracked_classes);
    EXPECT_EQ(ct.min_score, dt.min_score);
    EXPECT_EQ(ct.score_transform, dt.score_transform);
    EXPECT_EQ(ct.out_of_range, dt.out_of_range);
    EXPECT_EQ(ct.max_unobserved_s, dt.max_unobserved_s);
    EXPECT_EQ(ct.max_floor_gap_m, dt.max_floor_gap_m);
    EXPECT_EQ(ct.merge_iou, dt.merge_iou);
    EXPECT_EQ(ct.motion_gate_sigma, dt.motion_gate_sigma);
    for (std::size_t c2 = 0; c2 < dt.motion.size(); ++c2) {
        EXPECT_EQ(ct.motion[c2].velocity_decay_s, dt.motion[c2].velocity_decay_s);
        EXPECT_EQ(ct.motion[c2].max_speed_mps, dt.motion[c2].max_speed_mps);
        EXPECT_EQ(ct.motion[c2].planar, dt.motion[c2].planar);
        EXPECT_EQ(ct.motion[c2].min_displacement_m, dt.motion[c2].min_displacement_m);
        EXPECT_EQ(ct.motion[c2].motion_window_s, dt.motion[c2].motion_window_s);
    }
    EXPECT_EQ(c.system.navigator.astar.cost_weight, d.system.navigator.astar.cost_weight);
    const auto& cm = c.system.navigator.monitor;  // the collision monitor's keys (the robot's fill the rest)
    const auto& dm = d.system.navigator.monitor;
    EXPECT_EQ(cm.enabled, dm.enabled);
    EXPECT_EQ(cm.latency_s, dm.latency_s);
    EXPECT_EQ(cm.min_points, dm.min_points);
    EXPECT_EQ(cm.stop_padding_m, dm.stop_padding_m);
    EXPECT_EQ(cm.slowdown_padding_m, dm.slowdown_padding_m);
    EXPECT_EQ(cm.slowdown_time_s, dm.slowdown_time_s);
    EXPECT_EQ(cm.slowdown_ratio, dm.slowdown_ratio);
    EXPECT_EQ(cm.time_before_collision_s, dm.time_before_collision_s);
    EXPECT_EQ(cm.simulation_time_step_s, dm.simulation_time_step_s);
    EXPECT_EQ(cm.dynamic_speed_mps, dm.dynamic_speed_mps);
    EXPECT_EQ(cm.dynamic_history, dm.dynamic_history);
    EXPECT_EQ(cm.dynamic_min_height_m, dm.dynamic_min_height_m);
    EXPECT_EQ(cm.min_scale, dm.min_scale);
    EXPECT_EQ(cm.lowest_beam_deg, dm.lowest_beam_deg);
    EXPECT_EQ(cm.blind_memory_s, dm.blind_memory_s);
    EXPECT_EQ(cm.max_range_m, dm.max_range_m);
    EXPECT_EQ(cm.recovery_after_s, dm.recovery_after_s);
    EXPECT_EQ(cm.backup_speed_mps, dm.backup_speed_mps);
    EXPECT_EQ(cm.backup_distance_m, dm.backup_distance_m);
    EXPECT_EQ(cm.rotate_speed_radps, dm.rotate_speed_radps);
    EXPECT_EQ(cm.rotate_angle_rad, dm.rotate_angle_rad);
}

TEST(Config, CollisionMonitorProblemsAreListedWithTheirSection) {
    try {
        parse_sim_config("collision_monitor: {slowdown_ratio: 0, stop_paddin_m: 0.1}\n");
        FAIL() << "accepted a bad collision_monitor section";
    } catch (const FormatError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("collision_monitor"), std::string::npos) << what;
        EXPECT_NE(what.find("slowdown_ratio"), std::string::npos) << what;
        EXPECT_NE(what.find("stop_paddin_m"), std::string::npos) << what;  // the unknown key, with a suggestion
    }
}

TEST(Config, TrackerIsConfigurable) {
    const SimConfig c = parse_sim_config("tracking: {classes: [chair], min_score: 0.3, score_transform: sigmoid, sensor_range_m: 25,\n"
                                  "  out_of_range: drop, max_unobserved_s: .inf, chair_velocity_decay_s: .inf, table_max_speed_mps: 0.5}\n");
    const auto& t = c.system.tracker;
    EXPECT_TRUE(t.tracked_classes[0]);
    EXPECT_FALSE(t.tracked_classes[1]);
    EXPECT_EQ(t.min_score, 0.3);
    EXPECT_EQ(t.score_transform, makeway::tracking::ScoreTransform::kSigmoid);
    EXPECT_EQ(t.sensor_range_m, 25.0);
    EXPECT_EQ(t.out_of_range, makeway::tracking::OutOfRange::kDrop);
    EXPECT_TRUE(std::isinf(t.max_unobserved_s));
    EXPECT_TRUE(std::isinf(t.motion[0].velocity_decay_s));
    EXPECT_EQ(t.motion[1].max_speed_mps, 0.5);
    try {
        parse_sim_config("tracking: {classes: [sofa], score_transform: softmax, out_of_range: sideways, sensor_range_m: .inf}\n");
        ADD_FAILURE();
    } catch (const FormatError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("unknown class 'sofa'"), std::string::npos) << what;
        EXPECT_NE(what.find("score_transform: must be none or sigmoid"), std::string::npos) << what;
        EXPECT_NE(what.find("out_of_range: must be freeze or drop"), std::string::npos) << what;
        EXPECT_NE(what.find("sensor_range_m: must be finite"), std::string::npos) << what;
    }
}

TEST(Config, AffordanceZonesArePerClassParameters) {
    const SimConfig c = parse_sim_config("affordance:\n  chair:\n    forward_back_m: 0.9\n  table:\n    sides_m: 1.0\n");
    EXPECT_EQ(c.affordance.chair.forward_back_m, 0.9);
    EXPECT_EQ(c.affordance.table.sides_m, 1.0);
    EXPECT_EQ(problem_of("affordance:\n  chair:\n    peak_cost: 300\n"),
              "affordance.chair.peak_cost must be in [0.000000, 252.000000] (got 300.000000)");
    EXPECT_EQ(problem_of("affordance:\n  sofa:\n    side_m: 1\n"), "affordance.sofa: unknown key");
}

TEST(Config, PartialFileKeepsDefaults) {
    const SimConfig c = parse_sim_config("scene:\n  density: dense\nsimulation:\n  frames: 5\n");
    EXPECT_EQ(c.scene.density, sim::Density::kDense);
    EXPECT_EQ(c.simulation.frames, 5);
    EXPECT_EQ(c.scene.layout, sim::Layout::kStudySpace);
    EXPECT_EQ(c.lidar.rate_hz, SimConfig{}.lidar.rate_hz);
    EXPECT_EQ(parse_sim_config("").simulation.frames, SimConfig{}.simulation.frames);
}

TEST(Config, UnknownKeyGetsASuggestion) {
    EXPECT_EQ(problem_of("lidar:\n  range_noise: 0.1\n"),
              "lidar.range_noise: unknown key (did you mean 'range_noise_m'?)");
    EXPECT_EQ(problem_of("colour:\n  red: 1\n"), "colour: unknown section");
}

TEST(Config, OutOfRangeAndWrongTypes) {
    EXPECT_EQ(problem_of("lidar:\n  rate_hz: -3\n"), "lidar.rate_hz must be in [1, 50]");
    EXPECT_EQ(problem_of("simulation:\n  frames: many\n"), "simulation.frames: must be an integer");
    EXPECT_NE(problem_of("lidar:\n  range_noise_m: .nan\n").find("lidar.range_noise_m: must be finite"),
              std::string::npos);
    EXPECT_EQ(problem_of("scene:\n  people: perhaps\n"), "scene.people: must be true or false");
    EXPECT_EQ(problem_of("scene:\n  density: crowded\n"),
              "scene: density must be sparse, medium or dense (got 'crowded')");
    EXPECT_EQ(problem_of("robot: 3\n"), "robot: must be a mapping of keys to values");
    EXPECT_EQ(problem_of("scene:\n  seed: -1\n"), "scene.seed: must be a non-negative integer");
}

TEST(Config, EveryProblemListedAtOnce) {
    const std::string msg = problem_of(
        "simulation:\n  frames: 0\nlidar:\n  rate_hs: 3\n  dropout: 7\nrobot:\n  max_v_mps: x\n");
    EXPECT_EQ(msg.rfind("4 problems: ", 0), 0u) << msg;
    for (const char* part : {"lidar.rate_hs: unknown key (did you mean 'rate_hz'?)", "simulation.frames must be in",
                             "lidar.dropout must be in", "robot.max_v_mps: must be a number"}) {
        EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
    }
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(Config, SyntaxErrorsAndFiles) {
    EXPECT_NE(problem_of("scene:\n  seed: [1, 2\n").find("YAML syntax error at line"), std::string::npos);
    EXPECT_EQ(problem_of("- a\n- b\n"), "the top level must be a mapping of section names");
    const auto dir = testing_util::fresh_dir("cfg");
    std::ofstream(dir / "c.yaml") << "simulation:\n  frames: -2\n";
    try {
        load_sim_config(dir / "c.yaml");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()).rfind((dir / "c.yaml").string() + ": simulation.frames", 0), 0u) << e.what();
    }
    EXPECT_THROW(load_sim_config(dir / "missing.yaml"), FileError);
}

// The robot's program reads the same file without the simulator: the simulator's sections are
// skipped (a typo in them is the simulator's business), everything else is read and checked alike.
TEST(Config, TheRobotsReaderSkipsTheSimulatorsSections) {
    const std::string yaml = "scene:\n  density: crowded\nlidar:\n  rate_hs: 3\nrobot:\n  max_v_mps: 0.5\n";
    const Config robot_side = parse_config(yaml);
    EXPECT_EQ(robot_side.robot.max_v_mps, 0.5);
    EXPECT_NE(problem_of(yaml).find("2 problems"), std::string::npos) << problem_of(yaml);
    const SimConfig both = parse_sim_config("robot:\n  max_v_mps: 0.5\n");
    EXPECT_EQ(both.robot.max_v_mps, 0.5);
    EXPECT_EQ(both.scene.robot.max_v_mps, 0.5);  // the simulated robot is the described one
    try {
        parse_config("robot:\n  max_v_mps: x\ncolour: 1\n");
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()), "2 problems: colour: unknown section; robot.max_v_mps: must be a number");
    }
}

}  // namespace
}  // namespace makeway::io

namespace makeway::io {
namespace {

// Every numeric key of the shipped file, tried with the values a damaged or careless file holds
// (-1, 0, -1e308, 1e308, NaN, a word): refused with one line naming the section, or admitted by
// the key's bounds; no key admits -1e308, NaN or a word.
TEST(Config, EveryNumericKeyRefusesNonsense) {
    std::ifstream in(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml");
    std::string line, section;
    std::vector<std::pair<std::string, std::string>> keys;  // (section, key)
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (line[0] != ' ') {
            section = line.substr(0, line.find(':'));
            continue;
        }
        const std::size_t colon = line.find(':');
        if (line.rfind("  ", 0) != 0 || line[2] == ' ' || colon == std::string::npos) continue;
        std::string value = line.substr(colon + 1);
        value = value.substr(0, value.find('#'));
        value.erase(0, value.find_first_not_of(' '));
        value.erase(value.find_last_not_of(' ') + 1);
        char* end = nullptr;
        std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0') continue;  // not a number (names, lists, booleans)
        keys.emplace_back(section, line.substr(2, colon - 2));
    }
    ASSERT_GT(keys.size(), 150u);
    std::vector<std::string> accepted;
    for (const auto& [sec, key] : keys) {
        for (const char* bad : {"-1", "0", "-1e308", "1e308", ".nan", "text"}) {
            const std::string problem = problem_of(sec + ":\n  " + key + ": " + bad + "\n");
            if (problem.empty()) {
                accepted.push_back(sec + "." + key + "=" + bad);
                continue;
            }
            EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
            EXPECT_NE(problem.find(sec), std::string::npos) << sec << "." << key << "=" << bad << ": " << problem;
        }
    }
    // None of these is bounded from below: a damaged file's -1e308 or the string ends here. (The
    // upper bounds are the parameters issue's: each key's bounds in one table.)
    for (const std::string& a : accepted) {
        EXPECT_EQ(a.find("=-1e308"), std::string::npos) << a << " accepted";
        EXPECT_EQ(a.find("=.nan"), std::string::npos) << a << " accepted";
        EXPECT_EQ(a.find("=text"), std::string::npos) << a << " accepted";
    }
}

}  // namespace
}  // namespace makeway::io
