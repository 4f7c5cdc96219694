#pragma once
// One function per subcommand. main.cpp alone parses the command line (CLI11 is slow to compile)
// and fills these option structs. Each returns the process exit code: 0 success, 2 bad input.
#include <string>

namespace makeway::apps {

constexpr int kExitBadInput = 2;

struct InfoOptions {
    std::string path;
};
int run_info(const InfoOptions& options);

struct ConvertOptions {
    std::string input;
    std::string output;
    std::string pcd_encoding = "binary";
    std::string ply_encoding = "binary";
    std::string non_finite = "reject";
};
int run_convert(const ConvertOptions& options);

struct DemoOptions {
    std::string config;  ///< empty: built-in defaults
    std::string out_dir = "out/demo";
};
int run_demo(const DemoOptions& options);

/// Prints "makeway: MESSAGE" to stderr.
void print_error(const std::string& message);
void print_warning(const std::string& message);

}  // namespace makeway::apps
