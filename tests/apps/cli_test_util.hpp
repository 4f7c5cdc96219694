#pragma once
// Runs the makeway program from the tests of tests/apps: exit code, standard output and error.
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace makeway::testing_util {

struct CliRun {
    int exit_code = -1;
    std::string out;
    std::string err;
};

/// Runs the makeway binary (MAKEWAY_BIN, set by tests/apps/CMakeLists.txt) with `args`
/// (shell-quoted by the caller), capturing both streams.
inline CliRun run_makeway(const std::string& args, const std::filesystem::path& dir);

/// Runs a shell command line (sh -c), capturing both streams.
inline CliRun run_shell(const std::string& command_line, const std::filesystem::path& dir) {
    const auto err_path = dir / "stderr.txt";
    const std::string cmd = command_line + " 2>" + err_path.string();
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    while (std::size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.out.append(buf.data(), n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(err_path);
    r.err.assign(std::istreambuf_iterator<char>(in), {});
    return r;
}

inline CliRun run_makeway(const std::string& args, const std::filesystem::path& dir) {
    return run_shell(std::string(MAKEWAY_BIN) + " " + args, dir);
}

/// A file's bytes (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Lines written to a stream (its newlines).
inline std::size_t lines(const std::string& s) {
    return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace makeway::testing_util
