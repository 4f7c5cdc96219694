// The networks are a module opened on first use (perception/neural_module.hpp): what loads it,
// what does not, and what a command says without it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/point_cloud_io.hpp"
#include "makeway/perception/neural_module.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_shell;

// The networks are a module opened on first use (perception/neural_module.hpp): a command that runs
// none never loads libtorch (0.7 s per start, 2 s under ASan), and one that does loads it then.
TEST(Cli, OnlyACommandThatRunsANetworkLoadsTorch) {
    const auto dir = testing_util::fresh_dir("lazy_torch");
    io::write_point_cloud(dir / "c.pcd", testing_util::random_cloud(1, 100, PointFields::all()));
    // The dynamic loader lists every file it opens (LD_DEBUG=files) on standard error.
    const auto loaded = [&](const std::string& args) {
        const CliRun r = run_shell("LD_DEBUG=files " + std::string(MAKEWAY_BIN) + " " + args, dir);
        EXPECT_NE(r.err.find("libc.so"), std::string::npos) << "the loader listed nothing";
        return r.err;
    };
    const std::string info = loaded("info " + (dir / "c.pcd").string());
    EXPECT_EQ(info.find("libtorch"), std::string::npos);
    EXPECT_EQ(info.find(perception::kNeuralModuleFile), std::string::npos);
    const std::string detect = loaded(
        "detect --cloud " + (dir / "c.pcd").string() + " --out " + (dir / "dets.json").string() +
        " --model " + (std::filesystem::path(MAKEWAY_SOURCE_DIR) / "models/detector.pt").string());
    EXPECT_TRUE(std::filesystem::exists(dir / "dets.json"));
    EXPECT_NE(detect.find(perception::kNeuralModuleFile), std::string::npos);
    EXPECT_NE(detect.find("libtorch_cpu"), std::string::npos);
    // `detect` with MAKEWAY_NEURAL_MODULE naming `module`: exit 1, one line saying `expected`,
    // nothing written.
    const auto refused = [&](const std::string& module, const std::string& expected) {
        const CliRun r =
            run_shell("MAKEWAY_NEURAL_MODULE=" + module + " " + std::string(MAKEWAY_BIN) +
                          " detect --cloud " + (dir / "c.pcd").string() + " --out " +
                          (dir / "again.json").string(),
                      dir);
        EXPECT_EQ(r.exit_code, 1) << module;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "again.json")) << module;
    };
    // Without the module a network cannot run: the file tried is named.
    refused((dir / "gone.so").string(), (dir / "gone.so").string() + ": no such file");
    // A module that loads but lacks the network (built with -DMAKEWAY_SHAPE_NETWORKS=OFF, or from
    // other sources): the module and the missing function are named.
    refused(MAKEWAY_MODULE_WITHOUT_NETWORKS,
            std::string(MAKEWAY_MODULE_WITHOUT_NETWORKS) + ": no symbol makeway_detector_backend");
}

}  // namespace
}  // namespace makeway
