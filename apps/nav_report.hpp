#pragma once
// Navigation results as JSON and as the paper's Table II (markdown) with bootstrap intervals and
// paired differences, and the risk-vs-time picture. Everything in results.json is a function of
// the runs' JSON alone, so one run and merged shards give the same bytes; wall-clock timing (the
// control cycle, the keyframe chain) lives apart, in timing.json.
#include <filesystem>
#include <string>
#include <vector>

#include "io/json_io.hpp"
#include "io/sim_config.hpp"
#include "makeway/eval/navigation.hpp"

namespace makeway::apps {

/// Navigation parameters from a configuration (lidar, robot and affordance sections).
eval::NavParams nav_params(const io::SimConfig& config);

/// A run's deterministic fields (results.json; with_trajectory adds the true and believed paths).
io::Json run_to_json(const eval::NavRunResult& r, bool with_trajectory);
/// A run's wall-clock fields (timing.json): control cycle and keyframe chain medians and p99.
io::Json run_timing_json(const eval::NavRunResult& r);

/// Median and 99th percentile of a sample.
std::pair<double, double> median_p99(const std::vector<double>& values);

/// results.json from `header` ({scenes, seed, methods, time_limit_s, config}) and every run's JSON
/// (each with scene, scene_index, density), in scene then method order: per method the paper's
/// sums and means over successful runs, means with 95 % bootstrap intervals, avoidable risk
/// (risk - unavoidable), and paired differences between methods on the same scenes.
io::Json summarise_nav(const io::Json& header, const io::Json& runs);
/// Per method: control cycle and keyframe chain (medians of the runs' medians, p99 of their p99s).
io::Json summarise_timing(const io::Json& timing, const std::vector<std::string>& methods);

/// table.md: the paper's Table II columns plus intervals, then the paired differences.
std::string nav_table_markdown(const io::Json& summary);
/// risk_time.png: each method's runs as points, total time (x) against risk time (y), successful
/// runs.
void write_risk_time_plot(const std::filesystem::path& path, const io::Json& summary);

}  // namespace makeway::apps
