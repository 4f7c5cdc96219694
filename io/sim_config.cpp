#include "io/sim_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>


namespace makeway::io {

namespace {

void read_sim_sections(const YAML::Node& const_root, SimConfig& cfg, std::vector<std::string>& problems) {
    {
        YamlSection s(const_root["scene"], "scene", problems);
        std::string density(sim::to_string(cfg.scene.density));
        std::string layout = cfg.scene.layout == sim::Layout::kStudySpace ? "study_space" : "random";
        s.read("seed", cfg.scene.seed);
        s.read("density", density);
        s.read("layout", layout);
        s.read("people", cfg.scene.people);
        s.finish();
        if (const auto d = sim::parse_density(density)) {
            cfg.scene.density = *d;
        } else {
            s.problem("density must be sparse, medium or dense (got '" + density + "')");
        }
        if (const auto l = sim::parse_layout(layout)) {
            cfg.scene.layout = *l;
        } else {
            s.problem("layout must be random or study_space (got '" + layout + "')");
        }
    }
    {
        YamlSection s(const_root["lidar"], "lidar", problems);
        sim::LidarParams& l = cfg.lidar;
        s.read("azimuth_step_deg", l.azimuth_step_deg);
        s.read("rate_hz", l.rate_hz);
        s.read("min_range_m", l.min_range_m);
        s.read("max_range_m", l.max_range_m);
        s.read("range_noise_m", l.range_noise_m);
        s.read("dropout", l.dropout);
        s.read("intensity_falloff_m", l.intensity_falloff_m);
        s.read("intensity_speckle", l.intensity_speckle);
        s.read("intensity_noise", l.intensity_noise);
        s.read("time_slices", l.time_slices);
        s.read("num_threads", l.num_threads);
        s.read("use_packets", l.use_packets);
        s.finish();
        s.add_validation(l.validate());
    }
    {
        YamlSection s(const_root["odometry"], "odometry", problems);
        s.read("translation_noise_per_m", cfg.odometry.translation_noise_per_m);
        s.read("heading_noise_per_rad", cfg.odometry.heading_noise_per_rad);
        s.read("heading_noise_per_m", cfg.odometry.heading_noise_per_m);
        s.finish();
        s.add_validation(cfg.odometry.validate());
    }
    {
        YamlSection s(const_root["simulation"], "simulation", problems);
        s.read("frames", cfg.simulation.frames);
        s.read("seed", cfg.simulation.seed);
        s.finish();
        if (cfg.simulation.frames < 1 || cfg.simulation.frames > 1000000) {
            s.add_validation({"frames must be in [1, 1000000] (got " + std::to_string(cfg.simulation.frames) + ")"});
        }
    }
    cfg.scene.robot = cfg.robot;  // the simulated robot is the described one
}

}  // namespace

SimConfig parse_sim_config(std::string_view yaml_text) {
    SimConfig config;
    detail::parse_into(yaml_text, config, [&](const YAML::Node& root, std::vector<std::string>& problems) {
        read_sim_sections(root, config, problems);
    });
    return config;
}

SimConfig load_sim_config(const std::filesystem::path& path) {
    SimConfig config;
    if (path.empty()) return config;
    detail::load_into(path, config, [&](const YAML::Node& root, std::vector<std::string>& problems) {
        read_sim_sections(root, config, problems);
    });
    return config;
}

}  // namespace makeway::io
