#pragma once
// Pictures of navigation runs: the costmap (lethal black, inscribed grey, soft costs yellow to red),
// the objects with their affordance-zone outlines, the mission and each method's driven path.
#include <filesystem>
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::io {

struct DrivenPath {
    std::string label;
    std::vector<Pose2> poses;
};

/// `costmap` may be empty (no grid drawn). Objects are drawn at t = 0 with their ground-truth
/// affordance zones as `zones` defines them (the risk-time zones of the run). Throws FileError.
void write_nav_png(const std::filesystem::path& path, const sim::Scene& scene, const Costmap& costmap,
                   const std::vector<DrivenPath>& paths, const std::vector<Eigen::Vector2d>& plan,
                   const std::string& title, const costmap::AffordanceParams& zones);

}  // namespace makeway::io
