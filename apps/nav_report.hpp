#pragma once
// Navigation results as JSON and as the paper's Table II (markdown).
#include <string>
#include <vector>

#include "io/config_reader.hpp"
#include "io/json_io.hpp"
#include "makeway/eval/navigation.hpp"

namespace makeway::apps {

/// Navigation parameters from a configuration (lidar, robot, affordance sections).
eval::NavParams nav_params(const io::Config& config);

io::Json run_to_json(const eval::NavRunResult& r, bool with_trajectory);

/// Aggregate per method over `runs` (means over successful runs, as in the paper).
io::Json aggregate_runs(const std::vector<eval::NavRunResult>& runs, const std::vector<std::string>& methods);

/// Median and 99th percentile of a sample.
std::pair<double, double> median_p99(const std::vector<double>& values);

std::string table_markdown(const io::Json& aggregate, const std::vector<std::string>& methods, int scenes);

}  // namespace makeway::apps
