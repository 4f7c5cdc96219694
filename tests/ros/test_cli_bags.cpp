// `makeway run` on recordings from the wild (issue 34): a bag whose structure is damaged, a bag
// with a damaged message among good ones, and an output that names the input. C++17 (rosbag
// writes the damaged copies), the program run as a user runs it.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "../apps/cli_test_util.hpp"
#include "../io/io_test_util.hpp"
#include "lying_message.hpp"

namespace makeway {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::fresh_dir;
using testing_util::lines;
using testing_util::run_makeway;
using testing_util::slurp;

// Nothing delivered and nothing half-written (staging folders) left in `dir` beside `keep`.
void expect_only(const fs::path& dir, std::vector<std::string> keep) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    std::sort(keep.begin(), keep.end());
    EXPECT_EQ(names, keep);
}

class RunOnRecordings : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = fresh_dir(
            "run_" +
            std::to_string(::getpid()));  // ctest runs each test in its own process, in parallel
        fs::copy_file(fs::path(MAKEWAY_SOURCE_DIR) / "tests" / "data" / "room_chair_table.yaml",
                      dir_ / "room.yaml");
        const CliRun r =
            run_makeway("simulate --scene " + (dir_ / "room.yaml").string() +
                            " --frames 8 --format bag --out " + (dir_ / "sim").string(),
                        dir_);
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    static fs::path bag() { return dir_ / "sim" / "drive.bag"; }
    static fs::path dir_;
};
fs::path RunOnRecordings::dir_;

TEST_F(RunOnRecordings, ADamagedStructureIsOneLineAndLeavesNothing) {
    const auto dir = fresh_dir("structure");
    std::string bytes = slurp(bag());
    const std::uint32_t huge = 0xFFFFFFF0u;  // the bag header's length: rosbag would allocate 4 GB
    std::memcpy(bytes.data() + 13, &huge, 4);
    std::ofstream(dir / "in.bag", std::ios::binary) << bytes;
    const CliRun r = run_makeway(
        "run --bag " + (dir / "in.bag").string() + " --out " + (dir / "out").string(), dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("in.bag: record at byte 13: declares a header of 4294967280 bytes"),
              std::string::npos)
        << r.err;
    expect_only(dir, {"in.bag", "stderr.txt"});
}

TEST_F(RunOnRecordings, ADamagedMessageIsNamedOrSkippedAndCounted) {
    const auto dir = fresh_dir("message");
    {
        // The recording again, sweep 3 cut to 200 bytes (a recorder that died mid-write).
        rosbag::Bag in(bag().string(), rosbag::bagmode::Read);
        rosbag::Bag out((dir / "in.bag").string(), rosbag::bagmode::Write);
        int sweep = 0;
        for (const rosbag::MessageInstance& m : rosbag::View(in)) {
            testing::LyingMessage copy = testing::as_bytes(m);
            if (m.getTopic() == "/velodyne_points" && sweep++ == 3) copy.bytes.resize(200);
            out.write(m.getTopic(), m.getTime(), copy, m.getConnectionHeader());
        }
    }
    CliRun r = run_makeway(
        "run --bag " + (dir / "in.bag").string() + " --png-every 0 --out " + (dir / "out").string(),
        dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("in.bag: /velodyne_points message 3 (bag time "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("data needs"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(--skip-bad-messages to skip such messages)"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));

    r = run_makeway("run --bag " + (dir / "in.bag").string() +
                        " --skip-bad-messages --png-every 0 --out " + (dir / "out").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;  // one warning for the skipped message
    EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
    const auto summary = nlohmann::json::parse(slurp(dir / "out" / "summary.json"));
    EXPECT_EQ(summary["sweeps"], 7);
    EXPECT_EQ(summary["skipped_messages"], 1);
}

TEST_F(RunOnRecordings, AnOutputNamingTheInputIsRefusedAndTheInputKept) {
    const auto dir = fresh_dir("overwrite");
    fs::copy_file(bag(), dir / "in.bag");
    const std::string before = slurp(dir / "in.bag");
    fs::create_symlink(dir / "in.bag", dir / "link.bag");
    fs::create_hard_link(dir / "in.bag", dir / "hard.bag");
    for (const char* out : {"in.bag", "link.bag", "hard.bag"}) {
        const CliRun r = run_makeway("run --bag " + (dir / "in.bag").string() + " --out-bag " +
                                         (dir / out).string() + " --out " + (dir / "out").string(),
                                     dir);
        EXPECT_EQ(r.exit_code, 2) << out << "\n" << r.err;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find("--out-bag names the input given as --bag"), std::string::npos)
            << r.err;
    }
    EXPECT_EQ(slurp(dir / "in.bag"), before);  // byte for byte
    expect_only(dir, {"in.bag", "link.bag", "hard.bag", "stderr.txt"});
}

}  // namespace
}  // namespace makeway
