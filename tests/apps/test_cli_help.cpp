// Every subcommand's --help, read from `makeway --help-all`.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::run_makeway;

// One subcommand's part of `--help-all`: its name, its description, its options and positionals
// without a description, and its own subcommands.
struct HelpSection {
    std::string name, description;
    std::vector<std::string> undescribed, children;
};

// CLI11 writes `--help-all` as: a group heading at column 0 ("Start here:"), then per subcommand
// its name at column 0, its description indented by 2, headings ("  Options:", "  Positionals:", "
// Subcommands:") and items indented by 4 with their description from column 32, or on the next line
// when the item is longer.
std::vector<HelpSection> expanded_help(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::vector<HelpSection> sections;
    bool started = false, in_children = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& line = lines[i];
        if (line.empty()) continue;
        if (line[0] != ' ') {
            if (line.back() == ':') {
                started |= line != "Options:" && line != "Positionals:";
            } else if (started) {
                sections.push_back({line, "", {}, {}});
                in_children = false;
            }
            continue;
        }
        if (sections.empty()) continue;
        HelpSection& s = sections.back();
        if (line == "  Options:" || line == "  Positionals:" || line == "  Subcommands:") {
            in_children = line == "  Subcommands:";
        } else if (line.rfind("    ", 0) != 0) {
            if (s.description.empty()) s.description = line.substr(2);
        } else if (line.size() > 4 && line[4] != ' ') {
            const std::string item = line.substr(4, line.find(' ', 4) - 4);
            if (in_children) {
                s.children.push_back(item);
                continue;
            }
            const bool here = line.size() > 32 && line[31] == ' ' && line[32] != ' ';
            const bool below = i + 1 < lines.size() &&
                               lines[i + 1].rfind(std::string(32, ' '), 0) == 0 &&
                               lines[i + 1].size() > 32;
            if (!here && !below) s.undescribed.push_back(item);
        }
    }
    return sections;
}

}  // namespace

// Every subcommand's help, from `--help-all` (and `bench --help-all` for the subcommands of
// `bench`: two processes, not one per subcommand, since each start loads libtorch): each says what
// it does, and every option and positional has a description.
TEST(Cli, HelpDescribesEveryOption) {
    const auto dir = testing_util::fresh_dir("help");
    const CliRun top = run_makeway("--help-all", dir);
    ASSERT_EQ(top.exit_code, 0) << top.err;
    std::vector<std::string> leaves;
    for (const HelpSection& s : expanded_help(top.out)) {
        std::vector<HelpSection> checked{s};
        if (!s.children.empty()) {
            const CliRun sub = run_makeway(s.name + " --help-all", dir);
            ASSERT_EQ(sub.exit_code, 0) << s.name << "\n" << sub.err;
            checked = expanded_help(sub.out);
            EXPECT_EQ(checked.size(), s.children.size()) << s.name;
            for (HelpSection& c : checked) c.name = s.name + " " + c.name;
        }
        for (const HelpSection& c : checked) {
            leaves.push_back(c.name);
            EXPECT_FALSE(c.description.empty()) << c.name << ": says nothing of what it does";
            EXPECT_TRUE(c.undescribed.empty())
                << c.name << ": no description for " << ::testing::PrintToString(c.undescribed);
        }
    }
    for (const char* known :
         {"info",           "config",         "convert",        "demo",        "cad",
          "scene",          "simulate",       "navigate",       "verify",      "label",
          "track",          "eval-tracking",  "odometry",       "run",         "dataset",
          "train-detector", "detect",         "eval-detection", "train-shape", "complete",
          "bench nav",      "bench merge",    "bench verify",   "bench track", "bench odometry",
          "bench label",    "bench sessions", "bench shape",    "bench sim"}) {
        EXPECT_NE(std::find(leaves.begin(), leaves.end(), known), leaves.end()) << known;
    }
    // One subcommand's own --help says the same.
    const CliRun conv = run_makeway("convert --help", dir);
    EXPECT_EQ(conv.exit_code, 0);
    for (const char* opt :
         {"--pcd-encoding", "--ply-encoding", "--non-finite", "=binary", "=reject"}) {
        EXPECT_NE(conv.out.find(opt), std::string::npos) << opt;
    }
}

}  // namespace makeway
