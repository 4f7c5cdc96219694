// All-or-nothing outputs (io::StagedOutput), marked recordings (io::RecordingFolder), the
// interrupt handler's deferral and the free-space check.
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <iterator>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/staged_output.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Every entry under `dir`, hidden ones included, as sorted relative paths.
std::vector<std::string> tree(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(StagedOutput, NewTargetAppearsWholeOnCommit) {
    const auto dir = testing_util::fresh_dir("new");
    {
        StagedOutput staged(dir / "out");
        write_file_atomic(staged.staging() / "a.txt", "a");
        write_file_atomic(staged.staging() / "sub" / "b.txt", "b");
        EXPECT_FALSE(fs::exists(dir / "out"));  // nothing visible before the commit
        staged.commit();
    }
    EXPECT_EQ(tree(dir),
              (std::vector<std::string>{"out", "out/a.txt", "out/sub", "out/sub/b.txt"}));
    EXPECT_EQ(slurp(dir / "out" / "sub" / "b.txt"), "b");
    // Folders get the permissions of any new folder, not mkdtemp's 0700.
    EXPECT_NE(fs::status(dir / "out").permissions() & fs::perms::others_read, fs::perms::none);
}

TEST(StagedOutput, ExistingTargetKeepsOtherFilesAndReplacesNamesakes) {
    const auto dir = testing_util::fresh_dir("existing");
    write_file_atomic(dir / "out" / "keep.txt", "keep");
    write_file_atomic(dir / "out" / "sub" / "b.txt", "old");
    {
        StagedOutput staged(dir / "out/");
        write_file_atomic(staged.staging() / "sub" / "b.txt", "new");
        staged.commit();
    }
    EXPECT_EQ(tree(dir),
              (std::vector<std::string>{"out", "out/keep.txt", "out/sub", "out/sub/b.txt"}));
    EXPECT_EQ(slurp(dir / "out" / "sub" / "b.txt"), "new");
    EXPECT_EQ(slurp(dir / "out" / "keep.txt"), "keep");
}

TEST(StagedOutput, FailureLeavesTheTargetAsItWas) {
    const auto dir = testing_util::fresh_dir("failure");
    // Without commit (an exception on the way): nothing, not even the staging folder.
    try {
        StagedOutput staged(dir / "out");
        write_file_atomic(staged.staging() / "a.txt", "a");
        throw std::runtime_error("later step failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_TRUE(tree(dir).empty());
    // A folder in the way of one file: checked before anything moves, so the other file is not
    // half-delivered (the order of a folder listing is arbitrary).
    fs::create_directories(dir / "out" / "z.png");
    {
        StagedOutput staged(dir / "out");
        write_file_atomic(staged.staging() / "a.txt", "a");
        write_file_atomic(staged.staging() / "z.png", "png");
        EXPECT_THROW(staged.commit(), FileError);
    }
    EXPECT_EQ(tree(dir), (std::vector<std::string>{"out", "out/z.png"}));
    // A file where the target folder goes.
    write_file_atomic(dir / "file", "x");
    EXPECT_THROW(StagedOutput(dir / "file"), FileError);
}

TEST(StagedOutput, InterruptIsDeferredThenStopsTheCommit) {
    const auto dir = testing_util::fresh_dir("interrupt");
    install_interrupt_handlers();
    {
        StagedOutput staged(dir / "out");
        std::raise(SIGINT);  // deferred: the process lives on, the flag is set
        EXPECT_TRUE(interrupt_requested());
        try {
            staged.commit();
            ADD_FAILURE() << "commit after an interrupt";
        } catch (const Interrupted& e) {
            EXPECT_EQ(e.exit_code(), 130);
        }
    }
    clear_interrupt_for_testing();
    EXPECT_TRUE(tree(dir).empty());
    // A file write under an interrupt lands whole (no .tmp left), then reports it.
    {
        const DeferInterrupts defer;
        std::raise(SIGTERM);
        try {
            write_file_atomic(dir / "a.txt", "whole");
            ADD_FAILURE() << "no Interrupted";
        } catch (const Interrupted& e) {
            EXPECT_EQ(e.exit_code(), 143);
        }
    }
    clear_interrupt_for_testing();
    EXPECT_EQ(tree(dir), std::vector<std::string>{"a.txt"});
    EXPECT_EQ(slurp(dir / "a.txt"), "whole");
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

TEST(RecordingFolder, MarkerUntilCompleteAndASummaryWhenStopped) {
    const auto dir = testing_util::fresh_dir("recording");
    write_file_atomic(dir / "rec" / "summary.json", "{\"complete\": true}");  // an earlier run's
    {
        RecordingFolder folder(dir / "rec", "simulate");
        EXPECT_TRUE(fs::exists(dir / "rec" / "PARTIAL"));
        EXPECT_FALSE(fs::exists(dir / "rec" / "summary.json"));  // never a stale "complete"
        folder.stopped({{"frames", 12}}, "disk full");
    }
    EXPECT_NE(slurp(dir / "rec" / "PARTIAL").find("disk full"), std::string::npos);
    const Json s = Json::parse(slurp(dir / "rec" / "summary.json"));
    EXPECT_EQ(s["complete"], false);
    EXPECT_EQ(s["frames"], 12);
    EXPECT_EQ(s["stopped"], "disk full");
    {
        RecordingFolder folder(dir / "rec", "simulate");
        folder.complete({{"frames", 20}});
    }
    EXPECT_FALSE(fs::exists(dir / "rec" / "PARTIAL"));
    EXPECT_EQ(Json::parse(slurp(dir / "rec" / "summary.json"))["complete"], true);
}

TEST(FreeSpace, ImpossibleAmountIsRefusedBeforeAnythingIsWritten) {
    const auto dir = testing_util::fresh_dir("space");
    try {
        check_free_space(dir / "not" / "yet", std::uintmax_t{1} << 62, "4 EB of sweeps");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("4 EB of sweeps need about"), std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(check_free_space(dir, 1000, "a small file"));
    EXPECT_FALSE(fs::exists(dir / "not"));
}

}  // namespace
}  // namespace makeway::io
