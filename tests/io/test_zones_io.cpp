// The zones file: what learn-zones writes is read back as it was, and a damaged or foreign file is
// one line naming the file and what is wrong.
#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/zones_io.hpp"
#include "io_test_util.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::io {
namespace {

TEST(ZonesFile, RoundTripsAndDrawsItself) {
    const auto dir = testing_util::fresh_dir("zones");
    costmap::LearnedZones z;
    z.kernel_m = 0.04;
    z.coverage_threshold = 0.15;
    z.prior_strength = 3.0;
    z.chair = costmap::ClassZone{
        12.0, {{-0.4, 0.0, deg_to_rad(5.0), 6.0}, {0.0, 0.05, 0.0, 18.0}}, {0.5, 0.45}};
    write_zones(dir / "zones.yaml", z, "learned from\ntwo lines");
    const costmap::LearnedZones back = read_zones(dir / "zones.yaml");
    EXPECT_EQ(back.kernel_m, 0.04);
    EXPECT_EQ(back.coverage_threshold, 0.15);
    EXPECT_EQ(back.prior_strength, 3.0);
    EXPECT_FALSE(back.table.has_value());
    ASSERT_TRUE(back.chair.has_value());
    EXPECT_EQ(back.chair->observations, 12.0);
    EXPECT_EQ(back.chair->typical_size_m, Eigen::Vector2d(0.5, 0.45));
    ASSERT_EQ(back.chair->motions.size(), 2u);
    EXPECT_EQ(back.chair->motions[0].dx_m, -0.4);
    EXPECT_NEAR(back.chair->motions[0].dyaw_rad, deg_to_rad(5.0), 1e-12);
    EXPECT_EQ(back.chair->motions[1].weight, 18.0);
    write_zones_png(dir / "zones.png", back, costmap::AffordanceParams{});
    EXPECT_GT(std::filesystem::file_size(dir / "zones.png"), 1000u);
}

TEST(ZonesFile, BadFilesAreOneLineNamingTheFileAndTheProblem) {
    const auto dir = testing_util::fresh_dir("bad_zones");
    const std::string head = "format: makeway_zones\nversion: 1\n";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"a: [1, 2\n", "YAML syntax error"},
        {"- 1\n- 2\n", "not a zones file"},
        {"format: other\n", "format must be makeway_zones"},
        {"format: makeway_zones\nversion: 7\n", "version 7 is not known"},
        {head + "kernel_m: -1\n", "kernel_m"},
        {head + "coverage_threshold: 1\n", "coverage_threshold"},
        {head + "chair: {observations: 3, motions: [[0, 0, 0]]}\n", "motions[0] must be"},
        {head + "chair: {observations: 3, motions: [[0, 0, 0, -1]]}\n", "weight >= 0"},
        {head + "chair: {observations: 3, motions: [[.nan, 0, 0, 1]]}\n", "finite"},
        {head + "chair: {observations: 3, motions: 4}\n", "motions must be a list"},
        {head + "chair: {observations: 1, motions: [[6, 0, 0, 1]]}\n", "<= 5 m"},
        {head + "kernel_m: 0.8\n", "kernel_m"},
        {head + "chair: {observations: 3}\n", "has observations but no motions"},
        {head + "chair: {observations: 1, motions: [[0, 0, 0, 1]], colour: red}\n",
         "chair.colour: unknown key"},
        {head + "sofa: {}\n", "sofa: unknown key"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto path = dir / ("z" + std::to_string(i) + ".yaml");
        std::ofstream(path) << cases[i].first;
        try {
            read_zones(path);
            ADD_FAILURE() << "accepted: " << cases[i].first;
        } catch (const FileError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
            EXPECT_NE(what.find(cases[i].second), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    EXPECT_THROW(read_zones(dir / "missing.yaml"), FileError);
}

}  // namespace
}  // namespace makeway::io
