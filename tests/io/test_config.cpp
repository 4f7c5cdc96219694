#include <gtest/gtest.h>

#include <fstream>

#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

std::string problem_of(const std::string& yaml) {
    try {
        parse_config(yaml);
    } catch (const FormatError& e) {
        return e.what();
    }
    return "";
}

TEST(Config, ShippedDefaultFileMatchesBuiltInDefaults) {
    const Config c = load_config(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml");
    const Config d;
    EXPECT_EQ(c.layout.seed, d.layout.seed);
    EXPECT_EQ(c.layout.num_objects, d.layout.num_objects);
    EXPECT_EQ(c.layout.room_size_m, d.layout.room_size_m);
    EXPECT_EQ(c.layout.table_share, d.layout.table_share);
    EXPECT_EQ(c.sampling.points_per_m2, d.sampling.points_per_m2);
    EXPECT_EQ(c.sampling.noise_m, d.sampling.noise_m);
    EXPECT_EQ(c.sampling.skip_bottom, d.sampling.skip_bottom);
}

TEST(Config, PartialFileKeepsDefaults) {
    const Config c = parse_config("layout:\n  num_objects: 5\n");
    EXPECT_EQ(c.layout.num_objects, 5);
    EXPECT_EQ(c.layout.room_size_m, Config{}.layout.room_size_m);
    EXPECT_EQ(parse_config("").layout.num_objects, Config{}.layout.num_objects);
}

TEST(Config, UnknownKeyGetsASuggestion) {
    EXPECT_EQ(problem_of("layout:\n  num_object: 5\n"),
              "layout.num_object: unknown key (did you mean 'num_objects'?)");
    EXPECT_EQ(problem_of("colour:\n  red: 1\n"), "colour: unknown section");
}

TEST(Config, OutOfRangeAndWrongTypes) {
    EXPECT_NE(problem_of("layout:\n  room_size_m: -3\n").find("layout.room_size_m must be in"),
              std::string::npos);
    EXPECT_EQ(problem_of("layout:\n  num_objects: many\n"), "layout.num_objects: must be an integer");
    EXPECT_NE(problem_of("sampling:\n  noise_m: .nan\n").find("must be finite"), std::string::npos);
    EXPECT_EQ(problem_of("sampling:\n  skip_bottom: perhaps\n"), "sampling.skip_bottom: must be true or false");
    EXPECT_EQ(problem_of("layout: 3\n"), "layout: must be a mapping of keys to values");
    EXPECT_EQ(problem_of("layout:\n  seed: -1\n"), "layout.seed: must be a non-negative integer");
}

TEST(Config, EveryProblemListedAtOnce) {
    const std::string msg = problem_of(
        "layout:\n  num_objects: 0\n  room_sise_m: 3\n  table_share: 7\nsampling:\n  noise_m: x\n");
    EXPECT_EQ(msg.rfind("4 problems: ", 0), 0u) << msg;
    for (const char* part : {"room_sise_m: unknown key", "num_objects must be in",
                             "table_share must be in", "sampling.noise_m: must be a number"}) {
        EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
    }
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(Config, SyntaxErrorsAndFiles) {
    EXPECT_NE(problem_of("layout:\n  seed: [1, 2\n").find("YAML syntax error at line"), std::string::npos);
    EXPECT_EQ(problem_of("- a\n- b\n"), "the top level must be a mapping of section names");
    const auto dir = testing_util::fresh_dir("cfg");
    std::ofstream(dir / "c.yaml") << "layout:\n  num_objects: -2\n";
    try {
        load_config(dir / "c.yaml");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()).rfind((dir / "c.yaml").string() + ": layout.num_objects", 0), 0u)
            << e.what();
    }
    EXPECT_THROW(load_config(dir / "missing.yaml"), FileError);
}

}  // namespace
}  // namespace makeway::io
