// The README's output promise at the program's edge (issue 14): a multi-file command delivers
// everything or nothing, whatever stops it (a write error, a full disk, Ctrl-C, `kill`), and a
// long recording that stops is marked PARTIAL with a summary of how far it got.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <thread>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"

namespace makeway {
namespace {
namespace fs = std::filesystem;

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;
using testing_util::slurp;

// Every entry under `dir` that a failed or interrupted run must not leave: staging folders and
// temporary files.
std::vector<std::string> leftovers(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name.find(".staging") != std::string::npos || name.find(".tmp.") != std::string::npos)
            out.push_back(e.path().string());
    }
    return out;
}

// Files in `dir`, temporary ones (still being written) not counted.
std::size_t count_files(const fs::path& dir) {
    std::error_code ec;
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir, ec))
        n += e.path().filename().string().find(".tmp.") == std::string::npos;
    return n;
}

// Starts makeway with `args` (no shell), stdout/stderr to files in `dir`.
pid_t spawn_makeway(const std::vector<std::string>& args, const fs::path& dir) {
    const pid_t pid = fork();
    if (pid == 0) {
        std::freopen((dir / "spawn_out.txt").c_str(), "w", stdout);
        std::freopen((dir / "spawn_err.txt").c_str(), "w", stderr);
        std::vector<char*> argv{const_cast<char*>(MAKEWAY_BIN)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(MAKEWAY_BIN, argv.data());
        _exit(127);
    }
    return pid;
}

// The exit code as a shell reports it: 128 + the signal for a process the signal ended (before
// the program installs its handlers, SIGINT ends it by default: same meaning, nothing written).
int wait_exit(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status)     ? WEXITSTATUS(status)
           : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                 : -1;
}

// Waits (at most 120 s) until `done` holds.
template <typename F>
bool eventually(F done) {
    const auto start = std::chrono::steady_clock::now();
    while (!done()) {
        if (std::chrono::steady_clock::now() - start > std::chrono::seconds(120)) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
}

class CliOutputs : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = testing_util::fresh_dir("outputs");
        const CliRun r =
            run_makeway("scene --seed 3 --out " + (dir_ / "scene" / "s.yaml").string(), dir_);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        scene_ = (dir_ / "scene" / "s.yaml").string();
    }
    fs::path dir_;
    std::string scene_;
};

TEST_F(CliOutputs, InterruptedRecordingIsMarkedAndEveryFrameOnDiskIsWhole) {
    for (const int sig : {SIGINT, SIGTERM}) {
        const fs::path rec = dir_ / ("rec" + std::to_string(sig));
        const pid_t pid = spawn_makeway(
            {"simulate", "--scene", scene_, "--frames", "5000", "--out", rec.string()}, dir_);
        ASSERT_TRUE(eventually([&] { return count_files(rec / "objects") >= 5; }));
        kill(pid, sig);
        EXPECT_EQ(wait_exit(pid), 128 + sig);
        EXPECT_NE(slurp(dir_ / "spawn_err.txt").find("makeway: interrupted by SIG"),
                  std::string::npos);
        ASSERT_TRUE(fs::exists(rec / "PARTIAL"));
        const io::Json s = io::Json::parse(slurp(rec / "summary.json"));
        EXPECT_EQ(s["complete"], false);
        const std::size_t frames = s["frames"].get<std::size_t>();
        EXPECT_GE(frames, 5u);
        EXPECT_LT(frames, 5000u);
        EXPECT_EQ(count_files(rec / "clouds"), frames);
        EXPECT_EQ(count_files(rec / "objects"), frames);
        EXPECT_EQ(lines(slurp(rec / "poses_gt.txt")), frames + 1)
            << "one header line and a pose per frame";
        EXPECT_EQ(lines(slurp(rec / "odometry.txt")), frames + 1);
    }
    EXPECT_TRUE(leftovers(dir_).empty());
}

TEST_F(CliOutputs, InterruptedNavigationWritesNothing) {
    // In the drive (nothing open yet) the program ends at once; nothing of the run is written.
    const fs::path out = dir_ / "nav";
    const pid_t pid = spawn_makeway(
        {"navigate", "--scene", scene_, "--method", "con", "--out", out.string()}, dir_);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the drive takes about 7 s
    kill(pid, SIGINT);
    EXPECT_EQ(wait_exit(pid), 130);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(leftovers(dir_).empty());
}

TEST_F(CliOutputs, FullDiskLeavesNoHalfOutput) {
    // A file-size limit makes every larger write fail as a full disk would (EFBIG instead of
    // ENOSPC). At most 85 KiB per file (bash counts KiB): gt-perc's run.json (60 KiB) and the
    // costmap (71 KiB) are written, the picture (89 KiB) is not; a 1.4 MB cloud is not.
    const auto limited = [&](const std::string& args) {
        return testing_util::run_shell("bash -c \"ulimit -f 85; trap '' XFSZ; exec " +
                                           std::string(MAKEWAY_BIN) + " " + args + "\"",
                                       dir_);
    };
    // Recording: the first cloud (1.4 MB) cannot be written.
    const std::string rec = (dir_ / "rec").string();
    CliRun r = limited("simulate --scene " + scene_ + " --frames 20 --out " + rec);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("write failed: File too large"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(fs::path(rec) / "PARTIAL"));
    EXPECT_EQ(io::Json::parse(slurp(fs::path(rec) / "summary.json"))["frames"], 0);
    EXPECT_EQ(count_files(fs::path(rec) / "clouds"), 0u);
    // Navigation: run.json and the costmap fit, the picture does not: none of them is delivered,
    // and the error names the file the user asked for, not the staging folder.
    r = limited("navigate --scene " + scene_ + " --method gt-perc --out " +
                (dir_ / "nav").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err, "makeway: " + (dir_ / "nav" / "route.png").string() +
                         ": write failed: File too large\n");
    EXPECT_FALSE(fs::exists(dir_ / "nav"));
    EXPECT_TRUE(leftovers(dir_).empty());
}

TEST(Cli, ShardedBenchNavMergesToTheSameBytes) {
    // Three scenes, two methods, a coarse sensor; once whole, once as 2 shards merged in reverse
    // order: results.json must be byte for byte the same; a missing or repeated shard is refused.
    const auto dir = testing_util::fresh_dir("bench_merge");
    std::ofstream(dir / "fast.yaml") << "lidar:\n  azimuth_step_deg: 1.0\n";
    const std::string common =
        "bench nav --scenes 3 --methods oppo,gt-perc --time-limit 12 --threads 1 --config " +
        (dir / "fast.yaml").string();
    ASSERT_EQ(run_makeway(common + " --out " + (dir / "whole").string(), dir).exit_code, 0);
    for (int k = 0; k < 2; ++k) {
        const CliRun r = run_makeway(common + " --shard " + std::to_string(k) + "/2 --out " +
                                         (dir / ("s" + std::to_string(k))).string(),
                                     dir);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / ("s" + std::to_string(k)) / "results.json"));
    }
    const io::Json s0 = io::read_json(dir / "s0" / "partial.json");
    EXPECT_EQ(s0["runs"].size(), 4u);  // scenes 0 and 2
    CliRun r = run_makeway("bench merge " + (dir / "s1").string() + " " + (dir / "s0").string() +
                               " --out " + (dir / "merged").string(),
                           dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(io::read_file(dir / "merged" / "results.json"),
              io::read_file(dir / "whole" / "results.json"));
    EXPECT_EQ(io::read_file(dir / "merged" / "table.md"),
              io::read_file(dir / "whole" / "table.md"));
    for (const char* f :
         {"risk_time.png", "timing.json", "scenes/sparse_0.yaml", "routes/dense_2.png"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / "merged" / f)) << f;
    }
    const io::Json whole = io::read_json(dir / "whole" / "results.json");
    EXPECT_EQ(whole["runs"].size(), 6u);
    EXPECT_TRUE(whole["aggregate"]["gt-perc"]["interval_95"].contains("avoidable_risk_s"));
    EXPECT_EQ(whole["paired"][0]["a"], "gt-perc");
    // Refused, one line, exit 2, nothing written: a missing shard, a shard twice, a bad --shard.
    r = run_makeway("bench merge " + (dir / "s0").string() + " --out " + (dir / "m2").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("shard 1/2 is missing"), std::string::npos) << r.err;
    r = run_makeway("bench merge " + (dir / "s0").string() + " " + (dir / "s0").string() +
                        " --out " + (dir / "m3").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("given twice"), std::string::npos) << r.err;
    EXPECT_EQ(run_makeway(common + " --shard 2/2 --out " + (dir / "bad").string(), dir).exit_code,
              2);
    for (const char* d : {"m2", "m3", "bad"}) EXPECT_FALSE(std::filesystem::exists(dir / d)) << d;
}

}  // namespace
}  // namespace makeway
