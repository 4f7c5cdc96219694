#include "io/sim_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>
#include <vector>

#include "makeway/sim/param_tables.hpp"

namespace makeway::io {

namespace {

const ParamTable<SimulationConfig>& simulation_table() {
    static const ParamTable<SimulationConfig> t = [] {
        ParamTable<SimulationConfig> s;
        s.add("frames", &SimulationConfig::frames, closed(1, 1000000),
              "sweeps the demo records with full ground truth (10 per second)")
            .add("seed", &SimulationConfig::seed, closed(0.0, 1.8446744073709552e19),
                 "sensor noise and odometry drift");
        return s;
    }();
    return t;
}

// The simulator's own sections, in the order the file lists them among the others.
std::vector<BoundSection> simulator_sections(SimConfig& c) {
    std::vector<BoundSection> s;
    s.push_back(bind_section("scene", "the procedural scene `makeway demo` drives through",
                             sim::scene_gen_table(), c.scene));
    s.push_back(bind_section("lidar",
                             "the simulated LiDAR, by default a Velodyne Ultra Puck (VLP-32C)",
                             sim::lidar_table(), c.lidar));
    s.push_back(bind_section(
        "wheel_noise",
        "the simulated wheel odometry's drift; sigmas grow with the square root of the motion",
        sim::wheel_noise_table(), c.odometry));
    s.back().old_name = "odometry";
    s.push_back(bind_section("simulation", "", simulation_table(), c.simulation));
    return s;
}

void read_sim_sections(const YAML::Node& root, SimConfig& cfg, std::vector<std::string>& problems,
                       std::vector<std::string>& deprecated) {
    std::vector<BoundSection> sections = simulator_sections(cfg);
    read_sections(root, sections, problems, deprecated);
    cfg.scene.robot = cfg.robot;  // the simulated robot is the described one
}

}  // namespace

std::vector<BoundSection> sim_config_sections(SimConfig& c) {
    // The simulator's sections with the robot after the LiDAR (the simulated robot is the described
    // one), then the robot's software: the order config/default.yaml lists them in.
    std::vector<BoundSection> all = simulator_sections(c), ours = config_sections(c);
    const auto named = [](const char* name) {
        return [name](const BoundSection& s) { return s.name == name; };
    };
    const auto robot = std::find_if(ours.begin(), ours.end(), named("robot"));
    all.insert(std::find_if(all.begin(), all.end(), named("lidar")) + 1, std::move(*robot));
    ours.erase(robot);
    for (BoundSection& s : ours) all.push_back(std::move(s));
    return all;
}

std::string default_config_yaml() {
    SimConfig defaults;
    return write_sections(
        sim_config_sections(defaults),
        "# makeway configuration. Every key is optional: a missing key keeps its built-in default "
        "(shown).\n"
        "# Units are in the key names. `makeway demo --config FILE` and `makeway simulate --config "
        "FILE`\n"
        "# read it. Unknown keys, wrong types and out-of-range values are all reported at once.\n"
        "# Generated from the stages' parameter tables (`makeway config > config/default.yaml`);\n"
        "# `makeway config --describe` lists each key's admitted values and unit.\n");
}

SimConfig parse_sim_config(std::string_view yaml_text) {
    SimConfig config;
    detail::parse_into(yaml_text, config,
                       [&](const YAML::Node& root, std::vector<std::string>& problems,
                           std::vector<std::string>& deprecated) {
                           read_sim_sections(root, config, problems, deprecated);
                       });
    return config;
}

SimConfig load_sim_config(const std::filesystem::path& path) {
    SimConfig config;
    if (path.empty()) return config;
    detail::load_into(path, config,
                      [&](const YAML::Node& root, std::vector<std::string>& problems,
                          std::vector<std::string>& deprecated) {
                          read_sim_sections(root, config, problems, deprecated);
                      });
    return config;
}

}  // namespace makeway::io
