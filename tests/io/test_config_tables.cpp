// The configuration as the stages' parameter tables declare it: the shipped file is generated from
// them, every key of a file reaches its member and is written back from it, renamed keys still
// read.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/error.hpp"
#include "io/sim_config.hpp"
#include "makeway/common/param_table.hpp"

namespace makeway::io {
namespace {

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// config/default.yaml is what the tables say, value for value and doc for doc: a default changed in
// a struct, a key added to a table or a doc edited fails here until the file is regenerated.
TEST(ConfigTables, ShippedDefaultFileIsGeneratedFromTheTables) {
    const std::string file = read_text(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml");
    EXPECT_EQ(file, default_config_yaml()) << "regenerate it: makeway config > config/default.yaml";
    // And it reads back to the built-in defaults: written from them, read into them.
    SimConfig read = load_sim_config(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml"),
              defaults;
    EXPECT_EQ(write_sections(sim_config_sections(read), ""),
              write_sections(sim_config_sections(defaults), ""));
}

// A file that sets every key of the shipped file to another admitted value (the four renamed keys
// and the renamed section under their old names): each value reaches a member, and that member is
// written under the key.
TEST(ConfigTables, EveryKeyOfAFileReachesItsMember) {
    const std::string path = std::string(MAKEWAY_SOURCE_DIR) + "/tests/data/config_every_key.yaml";
    SimConfig c = load_sim_config(path);
    const YAML::Node in = YAML::LoadFile(path);
    const YAML::Node out = YAML::Load(write_sections(sim_config_sections(c), ""));
    std::size_t keys = 0, nested = 0;
    const auto same = [](const YAML::Node& a, const YAML::Node& b) {
        if (a.IsSequence()) return b.IsSequence() && YAML::Dump(a) == YAML::Dump(b);
        double x = 0, y = 0;
        if (YAML::convert<double>::decode(a, x) && YAML::convert<double>::decode(b, y))
            return x == y;
        return a.Scalar() == b.Scalar();
    };
    // The node of `key` ("group.key": in the nested mapping), under its old name where only that is
    // given. (Const nodes throughout: assigning to a YAML::Node writes into the document.)
    const auto at = [](const YAML::Node& root, const BoundSection& section, const BoundParam& p) {
        const std::size_t dot = p.key.find('.');
        const YAML::Node sec = root[section.name] || section.old_name.empty()
                                   ? root[section.name]
                                   : root[section.old_name];
        const YAML::Node map = dot == std::string::npos ? sec : sec[p.key.substr(0, dot)];
        const std::string key = dot == std::string::npos ? p.key : p.key.substr(dot + 1);
        return map[key] || p.old_key.empty() ? map[key] : map[p.old_key];
    };
    SimConfig defaults;
    const YAML::Node default_yaml = YAML::Load(write_sections(sim_config_sections(defaults), ""));
    for (const BoundSection& sec : sim_config_sections(defaults)) {
        for (const BoundParam& p : sec.params) {
            const YAML::Node v = at(in, sec, p), written = at(out, sec, p);
            ASSERT_TRUE(v) << sec.name << "." << p.key << " is not in the test file";
            EXPECT_TRUE(same(v, written)) << sec.name << "." << p.key << ": " << YAML::Dump(v)
                                          << " read, " << YAML::Dump(written) << " written";
            EXPECT_FALSE(same(v, at(default_yaml, sec, p)))
                << sec.name << "." << p.key
                << " is the default in the test file: it proves nothing";
            nested += p.key.find('.') != std::string::npos;
            ++keys;
        }
    }
    EXPECT_GT(keys, 200u);
    EXPECT_EQ(nested, 9u);  // affordance.chair.* and affordance.table.*
}

TEST(ConfigTables, RenamedKeysAreReadWithAWarning) {
    Config c;
    std::vector<std::string> deprecated;
    detail::parse_into(
        "costmap:\n  low_obstacle_range_m: 1.5\nlabelling:\n  cad_max_residual_m: 0.02\n", c, {},
        &deprecated);
    EXPECT_EQ(c.system.navigator.obstacle.low_mark_range_m, 1.5);
    EXPECT_EQ(c.labelling.verify.e_max_m, 0.02);
    ASSERT_EQ(deprecated.size(), 2u);
    EXPECT_EQ(deprecated[0],
              "costmap.low_obstacle_range_m is deprecated: it is now costmap.low_mark_range_m");
    EXPECT_EQ(deprecated[1],
              "labelling.cad_max_residual_m is deprecated: it is now labelling.verify_e_max_m");
    try {
        parse_config("costmap:\n  low_obstacle_range_m: 1.5\n  low_mark_range_m: 2\n");
        FAIL() << "both names accepted";
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "costmap: low_obstacle_range_m and low_mark_range_m both given "
                  "(low_obstacle_range_m is low_mark_range_m's old name)");
    }
}

// The simulator's `odometry` section is `wheel_noise` now (the online system's is lidar_odometry).
TEST(ConfigTables, TheRenamedSectionIsReadUnderItsOldName) {
    EXPECT_EQ(parse_sim_config("odometry:\n  translation_noise_per_m: 0.05\n")
                  .odometry.translation_noise_per_m,
              0.05);
    EXPECT_EQ(parse_sim_config("wheel_noise:\n  translation_noise_per_m: 0.04\n")
                  .odometry.translation_noise_per_m,
              0.04);
    EXPECT_EQ(parse_config("odometry:\n  translation_noise_per_m: 0.05\n").robot.max_v_mps,
              RobotDescription{}.max_v_mps);  // skipped
    try {
        parse_sim_config(
            "odometry:\n  heading_noise_per_m: 0.05\nwheel_noise:\n  heading_noise_per_m: 0.04\n");
        FAIL() << "both sections accepted";
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "odometry and wheel_noise: both given (odometry is wheel_noise's old name)");
    }
}

// The bounds come from the table: one message per key, naming the key as the file writes it, the
// admitted values and what was given.
TEST(ConfigTables, RangesAndRulesSpeakTheFilesKeys) {
    const auto problem = [](const std::string& yaml) {
        try {
            parse_sim_config(yaml);
        } catch (const FormatError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(problem("perception:\n  ground_iterations: 0\n"),
              "perception.ground_iterations must be in [1, 100000] (got 0)");
    EXPECT_EQ(problem("costmap:\n  inflation_cost_scaling: 1e308\n"),
              "costmap.inflation_cost_scaling must be in (0, 100) (got 1e+308)");
    EXPECT_EQ(problem("tracking:\n  chair_velocity_decay_s: -1\n"),
              "tracking.chair_velocity_decay_s must be in [0, 3600] or .inf (got -1)");
    EXPECT_EQ(problem("affordance:\n  table:\n    edge_cost: 250\n"),
              "affordance.table.edge_cost must be at most peak_cost");
    EXPECT_EQ(problem("lidar_odometry:\n  min_range_m: 50\n"),
              "lidar_odometry.needs 0 <= min_range_m < max_range_m");
    EXPECT_EQ(problem("planning:\n  dwa_horizon_s: 0.05\n"),
              "planning.need 0 < rollout_dt_s <= horizon_s");
    EXPECT_EQ(problem("tracking:\n  classes: [chair, sofa]\n"),
              "tracking.classes: must be a list of chair or table (e.g. [chair]) (got 'sofa')");
    // A NaN is one problem (not also an out-of-range one).
    EXPECT_EQ(problem("robot:\n  max_v_mps: .nan\n"), "robot.max_v_mps: must be finite");
}

TEST(ParamTable, RangesUnitsAndNumbers) {
    EXPECT_EQ(closed(0, 2).text(), "[0, 2]");
    EXPECT_EQ(above(0, 0.5).text(), "(0, 0.5]");
    EXPECT_EQ(open(0.05, 5).or_infinity().text(), "(0.05, 5) or .inf");
    EXPECT_TRUE(below(0, 1).contains(0.0));
    EXPECT_FALSE(below(0, 1).contains(1.0));
    EXPECT_FALSE(above(0, 1).contains(0.0));
    EXPECT_FALSE(closed(0, 1).contains(std::nan("")));
    EXPECT_FALSE(closed(0, 1).contains(INFINITY));
    EXPECT_TRUE(closed(0, 1).or_infinity().contains(INFINITY));
    EXPECT_FALSE(closed(0, 1).or_infinity().contains(-INFINITY));
    EXPECT_EQ(param_unit("max_ang_acc_radps2"), "rad/s^2");
    EXPECT_EQ(param_unit("turn_rate_radps"), "rad/s");
    EXPECT_EQ(param_unit("rotate_angle_rad"), "rad");
    EXPECT_EQ(param_unit("stop_padding_m"), "m");
    EXPECT_EQ(param_unit("min_points"), "");
    EXPECT_EQ(param_number(0.1), "0.1");
    EXPECT_EQ(param_number(100000), "100000");
    EXPECT_EQ(param_number(INFINITY), ".inf");
}

// A struct included twice under two prefixes keeps one value each; a nested include's rule names
// its mapping.
TEST(ParamTable, IncludedTablesKeepTheirOwnMembers) {
    struct Inner {
        double a_m = 1.0;
        double b_m = 2.0;
    };
    struct Outer {
        Inner left, right;
        int n = 3;
    };
    ParamTable<Inner> inner;
    inner.add("a_m", &Inner::a_m, closed(0, 10), "")
        .add("b_m", &Inner::b_m, closed(0, 10), "")
        .require([](const Inner& i) { return i.a_m < i.b_m; }, "a_m must be below b_m");
    ParamTable<Outer> outer;
    outer
        .include(
            "left_", [](Outer& o) -> Inner& { return o.left; }, inner)
        .include(
            "right.", [](Outer& o) -> Inner& { return o.right; }, inner)
        .add("n", &Outer::n, closed(1, 5), "");
    ASSERT_EQ(outer.entries().size(), 5u);
    EXPECT_EQ(outer.entries()[0].key, "left_a_m");
    EXPECT_EQ(outer.entries()[3].key, "right.b_m");
    Outer o;
    *std::get<double*>(outer.entries()[2].ref(o)) = 5.0;  // right.a_m
    *std::get<int*>(outer.entries()[4].ref(o)) = 9;
    EXPECT_EQ(o.right.a_m, 5.0);
    EXPECT_EQ(o.left.a_m, 1.0);
    const std::vector<std::string> p = outer.problems(o);
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0], "n must be in [1, 5] (got 9)");
    EXPECT_EQ(p[1], "right.a_m must be below b_m");
}

}  // namespace
}  // namespace makeway::io
