#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/error.hpp"
#include "io/sim_config.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

std::string config_problem_of(const std::string& yaml) {
    try {
        parse_sim_config(yaml);
    } catch (const FormatError& e) {
        return e.what();
    }
    return "";
}

TEST(Config, CollisionMonitorProblemsAreListedWithTheirSection) {
    try {
        parse_sim_config("collision_monitor: {slowdown_ratio: 0, stop_paddin_m: 0.1}\n");
        FAIL() << "accepted a bad collision_monitor section";
    } catch (const FormatError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("collision_monitor"), std::string::npos) << what;
        EXPECT_NE(what.find("slowdown_ratio"), std::string::npos) << what;
        EXPECT_NE(what.find("stop_paddin_m"), std::string::npos)
            << what;  // the unknown key, with a suggestion
    }
}

TEST(Config, TrackerIsConfigurable) {
    const SimConfig c = parse_sim_config(
        "tracking: {classes: [chair], min_score: 0.3, score_transform: sigmoid, sensor_range_m: "
        "25,\n"
        "  out_of_range: drop, max_unobserved_s: .inf, chair_velocity_decay_s: .inf, "
        "table_max_speed_mps: 0.5}\n");
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
        parse_sim_config(
            "tracking: {classes: [sofa], score_transform: softmax, out_of_range: sideways, "
            "sensor_range_m: .inf}\n");
        ADD_FAILURE();
    } catch (const FormatError& e) {
        const std::string what = e.what();
        EXPECT_NE(
            what.find("classes: must be a list of chair or table (e.g. [chair]) (got 'sofa')"),
            std::string::npos)
            << what;
        EXPECT_NE(what.find("score_transform: must be none or sigmoid (got 'softmax')"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("out_of_range: must be freeze or drop"), std::string::npos) << what;
        EXPECT_NE(what.find("sensor_range_m: must be finite"), std::string::npos) << what;
    }
}

TEST(Config, AffordanceZonesArePerClassParameters) {
    const SimConfig c = parse_sim_config(
        "affordance:\n  chair:\n    forward_back_m: 0.9\n  table:\n    sides_m: 1.0\n");
    EXPECT_EQ(c.affordance.chair.forward_back_m, 0.9);
    EXPECT_EQ(c.affordance.table.sides_m, 1.0);
    EXPECT_EQ(config_problem_of("affordance:\n  chair:\n    peak_cost: 300\n"),
              "affordance.chair.peak_cost must be in [0, 252] (got 300)");
    EXPECT_EQ(config_problem_of("affordance:\n  sofa:\n    side_m: 1\n"),
              "affordance.sofa: unknown key");
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
    EXPECT_EQ(config_problem_of("lidar:\n  range_noise: 0.1\n"),
              "lidar.range_noise: unknown key (did you mean 'range_noise_m'?)");
    EXPECT_EQ(config_problem_of("colour:\n  red: 1\n"), "colour: unknown section");
}

TEST(Config, OutOfRangeAndWrongTypes) {
    EXPECT_EQ(config_problem_of("lidar:\n  rate_hz: -3\n"),
              "lidar.rate_hz must be in [1, 50] (got -3)");
    EXPECT_EQ(config_problem_of("simulation:\n  frames: many\n"),
              "simulation.frames: must be an integer");
    EXPECT_NE(config_problem_of("lidar:\n  range_noise_m: .nan\n")
                  .find("lidar.range_noise_m: must be finite"),
              std::string::npos);
    EXPECT_EQ(config_problem_of("scene:\n  people: perhaps\n"),
              "scene.people: must be true or false");
    EXPECT_EQ(config_problem_of("scene:\n  density: crowded\n"),
              "scene.density: must be sparse, medium or dense (got 'crowded')");
    EXPECT_EQ(config_problem_of("robot: 3\n"), "robot: must be a mapping of keys to values");
    EXPECT_EQ(config_problem_of("scene:\n  seed: -1\n"),
              "scene.seed: must be a non-negative integer");
}

TEST(Config, EveryProblemListedAtOnce) {
    const std::string msg = config_problem_of(
        "simulation:\n  frames: 0\nlidar:\n  rate_hs: 3\n  dropout: 7\nrobot:\n  max_v_mps: x\n");
    EXPECT_EQ(msg.rfind("4 problems: ", 0), 0u) << msg;
    for (const char* part :
         {"lidar.rate_hs: unknown key (did you mean 'rate_hz'?)", "simulation.frames must be in",
          "lidar.dropout must be in", "robot.max_v_mps: must be a number"}) {
        EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
    }
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(Config, SyntaxErrorsAndFiles) {
    EXPECT_NE(config_problem_of("scene:\n  seed: [1, 2\n").find("YAML syntax error at line"),
              std::string::npos);
    EXPECT_EQ(config_problem_of("- a\n- b\n"), "the top level must be a mapping of section names");
    const auto dir = testing_util::fresh_dir("cfg");
    std::ofstream(dir / "c.yaml") << "simulation:\n  frames: -2\n";
    try {
        load_sim_config(dir / "c.yaml");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()).rfind((dir / "c.yaml").string() + ": simulation.frames", 0),
                  0u)
            << e.what();
    }
    EXPECT_THROW(load_sim_config(dir / "missing.yaml"), FileError);
}

// The robot's program reads the same file without the simulator: the simulator's sections are
// skipped (a typo in them is the simulator's business), everything else is read and checked alike.
TEST(Config, TheRobotsReaderSkipsTheSimulatorsSections) {
    const std::string yaml =
        "scene:\n  density: crowded\nlidar:\n  rate_hs: 3\nrobot:\n  max_v_mps: 0.5\n";
    const Config robot_side = parse_config(yaml);
    EXPECT_EQ(robot_side.robot.max_v_mps, 0.5);
    EXPECT_NE(config_problem_of(yaml).find("2 problems"), std::string::npos)
        << config_problem_of(yaml);
    const SimConfig both = parse_sim_config("robot:\n  max_v_mps: 0.5\n");
    EXPECT_EQ(both.robot.max_v_mps, 0.5);
    EXPECT_EQ(both.scene.robot.max_v_mps, 0.5);  // the simulated robot is the described one
    try {
        parse_config("robot:\n  max_v_mps: x\ncolour: 1\n");
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "2 problems: colour: unknown section; robot.max_v_mps: must be a number");
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
            const std::string problem = config_problem_of(sec + ":\n  " + key + ": " + bad + "\n");
            if (problem.empty()) {
                accepted.push_back(sec + "." + key + "=" + bad);
                continue;
            }
            EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
            EXPECT_NE(problem.find(sec), std::string::npos)
                << sec << "." << key << "=" << bad << ": " << problem;
        }
    }
    // Every key is bounded on both sides (its table's range): a damaged file's +-1e308, NaN or
    // word ends here.
    for (const std::string& a : accepted) {
        EXPECT_EQ(a.find("=-1e308"), std::string::npos) << a << " accepted";
        EXPECT_EQ(a.find("=1e308"), std::string::npos) << a << " accepted";
        EXPECT_EQ(a.find("=.nan"), std::string::npos) << a << " accepted";
        EXPECT_EQ(a.find("=text"), std::string::npos) << a << " accepted";
    }
}

}  // namespace
}  // namespace makeway::io
