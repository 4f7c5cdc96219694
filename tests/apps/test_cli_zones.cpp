// makeway learn-zones on labelled sessions written as makeway label writes them, its errors, the
// zones file used by a navigator, and bench zones' outputs.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/json_io.hpp"
#include "io/zones_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

// objects.json of `sessions` sessions of a room of four chairs in a row facing +y; chair 0 is
// pulled 0.5 m back (-y) in every odd session.
void write_labels(const std::filesystem::path& dir, int sessions) {
    std::filesystem::create_directories(dir);
    io::Json objects = io::Json::array();
    for (int s = 0; s < sessions; ++s) {
        for (int k = 0; k < 4; ++k) {
            const double y = k == 0 && s % 2 == 1 ? -0.5 : 0.0;
            objects.push_back({{"id", 100 * s + k},
                               {"session", s},
                               {"class", "chair"},
                               {"class_source", "cad"},
                               {"model", "chair_a"},
                               {"box_world",
                                {{"centre_m", {0.8 * k, y, 0.45}},
                                 {"size_m", {0.5, 0.5, 0.9}},
                                 {"yaw_rad", M_PI_2}}}});
        }
        objects.push_back(
            {{"id", 100 * s + 9},
             {"session", s},
             {"class", "unknown"},
             {"class_source", "unknown"},
             {"model", ""},
             {"box_world",
              {{"centre_m", {5.0, 5.0, 0.3}}, {"size_m", {0.4, 0.4, 0.6}}, {"yaw_rad", 0.0}}}});
    }
    io::write_json(dir / "objects.json", {{"objects", objects}});
}

TEST(Cli, LearnZonesFromLabelledSessionsAndDriveWithThem) {
    const auto dir = testing_util::fresh_dir("learn_zones");
    write_labels(dir / "room_a", 4);
    write_labels(dir / "room_b", 3);
    const std::string d = dir.string() + "/";
    const CliRun r = run_makeway(
        "learn-zones --labels " + d + "room_a " + d + "room_b --out " + d + "zones.yaml", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // 4 chairs x (6 + 3 session pairs) matched; chair 0 moved in 4 + 2 of them.
    EXPECT_NE(r.out.find("chair: 28 observations, 72 motions"), std::string::npos) << r.out;
    const costmap::LearnedZones z = io::read_zones(dir / "zones.yaml");
    ASSERT_TRUE(z.chair.has_value());
    EXPECT_FALSE(z.table.has_value());  // the unknown object teaches nothing
    EXPECT_DOUBLE_EQ(z.chair->observations, 36.0);
    EXPECT_TRUE(std::filesystem::exists(dir / "zones.png"));
    // The chair's zone reaches 0.5 m behind it and, pulled-out chairs being pushed back, in front.
    costmap::AffordanceParams a;
    a.learned = std::make_shared<const costmap::LearnedZones>(z);
    ObjectEstimate chair;
    chair.box_world = {{0.0, 0.0, 0.45}, {0.5, 0.5, 0.9}, 0.0};
    EXPECT_LE(costmap::zone_coordinate(chair, a, {-0.6, 0.0}), 1.0);
    EXPECT_LE(costmap::zone_coordinate(chair, a, {0.6, 0.0}), 1.0);
    // The navigator plans with the file: the ground-truth method reaches the goal untouched.
    ASSERT_EQ(run_makeway("scene --seed 0 --density sparse --out " + d + "s.yaml", dir).exit_code,
              0);
    const CliRun nav = run_makeway("navigate --scene " + d + "s.yaml --method gt-perc --zones " +
                                       d + "zones.yaml --time-limit 90 --out " + d + "nav_ok",
                                   dir);
    ASSERT_EQ(nav.exit_code, 0) << nav.err;
    const io::Json run = io::read_json(dir / "nav_ok" / "run.json");
    EXPECT_TRUE(run["success"].get<bool>()) << run["failure"];
    EXPECT_EQ(run["collisions"].get<int>(), 0);
    // A damaged file is one line and exit 2 before anything runs.
    std::ofstream(dir / "bad.yaml") << "format: makeway_zones\nversion: 1\nprior_strength: -2\n";
    const CliRun bad = run_makeway(
        "navigate --scene " + d + "missing.yaml --zones " + d + "bad.yaml --out " + d + "nav", dir);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(lines(bad.err), 1u) << bad.err;
}

TEST(Cli, LearnZonesRefusesWhatIsNotALabelOutput) {
    const auto dir = testing_util::fresh_dir("learn_zones_bad");
    const std::string d = dir.string() + "/";
    std::filesystem::create_directories(dir / "empty");
    CliRun r = run_makeway("learn-zones --labels " + d + "empty --out " + d + "z.yaml", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("objects.json is missing"), std::string::npos) << r.err;
    std::filesystem::create_directories(dir / "broken");
    std::ofstream(dir / "broken" / "objects.json")
        << R"({"objects": [{"session": 0, "class": "chair", "box_world": {"centre_m": [0, 0]}}]})";
    r = run_makeway("learn-zones --labels " + d + "broken --out " + d + "z.yaml", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("objects.json: objects[0]: box_world"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "z.yaml"));
    EXPECT_FALSE(std::filesystem::exists(dir / "z.png"));
}

TEST(Cli, LearnZonesFromTheObjectMapsTracks) {
    // A makeway run output: a chair tracked for 30 s at 2 Hz, pulled 0.5 m back at t = 12 s.
    const auto dir = testing_util::fresh_dir("learn_zones_tracks");
    std::filesystem::create_directories(dir / "drive" / "objects");
    for (int k = 0; k < 60; ++k) {
        const double t = 0.5 * k, x = t >= 12.0 ? -0.5 : 0.0;
        const io::Json frame = {
            {"frame", k},
            {"stamp_s", t},
            {"objects",
             {{{"id", 4},
               {"class", "chair"},
               {"existence", 0.9},
               {"box_world",
                {{"centre_m", {x, 0.0, 0.45}}, {"size_m", {0.5, 0.5, 0.9}}, {"yaw_rad", 0.0}}}}}}};
        char name[32];
        std::snprintf(name, sizeof name, "%06d.json", k);
        io::write_json(dir / "drive" / "objects" / name, frame);
    }
    const std::string d = dir.string() + "/";
    const CliRun r =
        run_makeway("learn-zones --tracks " + d + "drive --no-png --out " + d + "zones.yaml", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Samples at 0, 5, ..., 25 s: five motions, one of them the pull.
    EXPECT_NE(r.out.find("chair: 0 observations, 5 motions (both directions of each match; 5 "
                         "within tracks)"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "zones.png"));
    const CliRun none = run_makeway("learn-zones --out " + d + "z.yaml", dir);
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_EQ(lines(none.err), 1u) << none.err;
}

TEST(Cli, BenchZonesWritesItsTableAndTheZonesItLearned) {
    const auto dir = testing_util::fresh_dir("bench_zones");
    const CliRun r = run_makeway(
        "bench zones --scenes 1 --usage sideways --train-sessions 3 --test-sessions 2 --out " +
            (dir / "bz").string(),
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"summary.json", "table.md", "zones.yaml", "zones.png"})
        EXPECT_TRUE(std::filesystem::exists(dir / "bz" / f)) << f;
    const io::Json j = io::read_json(dir / "bz" / "summary.json");
    EXPECT_EQ(j["usage"], "sideways");
    EXPECT_GT(j["chair"]["objects"].get<int>(), 0);
    EXPECT_TRUE(io::read_zones(dir / "bz" / "zones.yaml").chair.has_value());
}

TEST(Cli, BenchNavPlansWithEachBuildingsOwnZones) {
    // --zones-sessions: each scene's zones learned from sessions of that building; risk scored
    // on its profile. Said in the results; with --zones, or from one session, refused.
    const auto dir = testing_util::fresh_dir("bench_nav_own_zones");
    std::ofstream(dir / "fast.yaml") << "lidar:\n  azimuth_step_deg: 1.0\n";
    const std::string common =
        "bench nav --scenes 1 --methods gt-perc --time-limit 12 --threads 1 --usage sideways "
        "--risk-zones truth-profile --config " +
        (dir / "fast.yaml").string();
    const CliRun r =
        run_makeway(common + " --zones-sessions 3 --out " + (dir / "own").string(), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json j = io::read_json(dir / "own" / "results.json");
    EXPECT_EQ(j["zones_sessions"], 3);
    EXPECT_EQ(j["runs"].size(), 1u);
    std::ofstream(dir / "zones.yaml") << "x";
    const std::vector<std::string> refused = {
        " --zones-sessions 1", " --zones-sessions 3 --zones " + (dir / "zones.yaml").string()};
    for (const std::string& bad : refused) {
        const CliRun e = run_makeway(common + bad + " --out " + (dir / "bad").string(), dir);
        EXPECT_EQ(e.exit_code, 2) << bad;
        EXPECT_EQ(lines(e.err), 1u) << e.err;
        EXPECT_NE(e.err.find("--zones-sessions"), std::string::npos) << e.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad")) << bad;
    }
}

}  // namespace
}  // namespace makeway
