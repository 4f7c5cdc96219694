#pragma once
// YAML configuration mapped onto Params structs. Every problem in a file is collected and reported
// at once: unknown keys (with a suggestion), wrong types, and each section's validate() messages.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "makeway/common/param_table.hpp"
#include "makeway/common/robot_description.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/labelling/labeller.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace YAML {
class Node;
}

namespace makeway::io {

/// A YAML document; throws FormatError("YAML syntax error at line N: ...") on a syntax error.
YAML::Node load_yaml(std::string_view text);

/// Reads the keys of one YAML mapping; missing keys keep the struct's defaults.
class YamlSection {
  public:
    YamlSection(const YAML::Node& node, std::string prefix, std::vector<std::string>& problems);
    ~YamlSection();
    YamlSection(const YamlSection&) = delete;
    YamlSection& operator=(const YamlSection&) = delete;

    void read(const char* key, double& value);
    /// A number that may also be `.inf` (YAML's infinity), for "never" limits.
    void read_or_infinity(const char* key, double& value);
    void read(const char* key, int& value);
    void read(const char* key, std::uint64_t& value);
    void read(const char* key, bool& value);
    void read(const char* key, std::string& value);
    void read(const char* key, std::uint32_t& value);
    /// A pair of numbers written as [a, b].
    void read(const char* key, Eigen::Vector2d& value);
    /// Whether the mapping holds `key` (reading nothing, marking nothing as known).
    bool has(const char* key) const;
    /// The raw node under `key` (null when absent), for lists and nested mappings.
    YAML::Node take(const char* key);
    /// Records a problem under this section's prefix.
    void problem(const std::string& message);

    /// Adds `messages` (from a Params validate()) under this section's prefix.
    void add_validation(const std::vector<std::string>& messages);
    /// Reports every key that no read() asked for. Call once, after the reads.
    void finish();

  private:
    template <typename T>
    void read_scalar(const char* key, T& value, const char* type_name);

    struct Impl;
    Impl* impl_;
    std::string prefix_;
    std::vector<std::string>& problems_;
    std::vector<std::string> known_keys_;
    bool allow_infinity_ = false;
};

/// The sections of a makeway configuration file that configure the robot's software (and the robot
/// it drives); config/default.yaml documents each key. The simulator's sections (scene, lidar,
/// wheel_noise, simulation) are read by io/sim_config.hpp: this reader accepts and skips them, so
/// one file configures the benchmark and the robot alike, and the program on the robot never links
/// the simulator.
struct Config {
    RobotDescription robot;                ///< footprint, heights, limits, sensor mount
    costmap::AffordanceParams affordance;  ///< zone shapes and cost profiles per class
    /// The online system: sections lidar_odometry, perception, verification, tracking, costmap,
    /// planning, collision_monitor (system.navigator.affordance is filled from `affordance`).
    pipeline::SystemParams system;
    /// The automatic annotation (`makeway label`); its front end is `system`'s.
    labelling::LabelParams labelling;
};

/// Top-level sections that belong to the simulator (io/sim_config.hpp).
inline const std::vector<std::string> kSimulatorSections{
    "scene", "lidar", "wheel_noise", "simulation", "odometry" /* wheel_noise's old name */};

/// The online system's parameters as the program runs it on a robot (`ours` in the benchmark,
/// `makeway run`, makeway_node): the configuration's sections, the affordance zones into the
/// navigator, and the robot description into every stage (pipeline::apply_robot). `T_base_sensor`:
/// measured extrinsics (null: the robot section's mount).
pipeline::SystemParams online_system_params(const Config& config,
                                            const Isometry3* T_base_sensor = nullptr);

/// Throws FormatError listing every problem ("3 problems: a; b; c").
Config parse_config(std::string_view yaml_text);
/// Throws FileError("PATH: ...") on a missing file or any problem in it.
/// An empty path (no --config given) gives the built-in defaults.
Config load_config(const std::filesystem::path& path);

namespace detail {
/// Reads the sections a derived configuration adds (io/sim_config.cpp), appending their problems
/// and the deprecated keys they read.
using MoreSections = std::function<void(const YAML::Node& root, std::vector<std::string>& problems,
                                        std::vector<std::string>& deprecated)>;
/// Config's sections of `yaml_text` into `config`, then `more`'s; throws FormatError listing every
/// problem of every section, or on a syntax error or a top level that is no mapping. Deprecated
/// keys that were read go to `deprecated`, or (null) one warning each on stderr.
void parse_into(std::string_view yaml_text, Config& config, const MoreSections& more,
                std::vector<std::string>* deprecated = nullptr);
/// parse_into on the file's text; throws FileError("PATH: ...") on a missing file or any problem.
void load_into(const std::filesystem::path& path, Config& config, const MoreSections& more);
}  // namespace detail

}  // namespace makeway::io
