#pragma once
// The simulator's sections of a makeway configuration file (scene, lidar, wheel_noise, simulation),
// with everything the robot's software reads (io/config_reader.hpp). Only the programs that
// simulate read these: the library is io_sim, and the robot's node links io without it.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "io/config_reader.hpp"
#include "io/config_sections.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::io {

/// The `simulation` section: how long and with which seed `makeway demo` records.
struct SimulationConfig {
    int frames = 50;         ///< sweeps recorded by the demo (10 per second)
    std::uint64_t seed = 0;  ///< sensor noise and odometry drift
};

/// A whole configuration file: the robot's software (Config) and the simulated world around it.
struct SimConfig : Config {
    SimConfig() = default;  // not an aggregate: GCC 12 misreads SimConfig{}'s base as uninitialised
    sim::SceneGenParams scene{.layout = sim::Layout::kStudySpace};  ///< the paper's real-world room
    sim::LidarParams lidar;
    sim::OdometryNoiseParams odometry;  ///< the simulated wheel odometry's drift
    SimulationConfig simulation;
};

/// Every section of a whole file, bound to `c`, in the order config/default.yaml lists them.
std::vector<BoundSection> sim_config_sections(SimConfig& c);
/// config/default.yaml as the stages' tables describe it (a test checks the file against it).
std::string default_config_yaml();

/// Throws FormatError listing every problem, of every section ("3 problems: a; b; c").
SimConfig parse_sim_config(std::string_view yaml_text);
/// Throws FileError("PATH: ...") on a missing file or any problem in it.
/// An empty path (no --config given) gives the built-in defaults.
SimConfig load_sim_config(const std::filesystem::path& path);

}  // namespace makeway::io
