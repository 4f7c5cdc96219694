#pragma once
// Pictures of navigation runs: the costmap (lethal black, inscribed grey, soft costs yellow to
// red), the objects with their affordance-zone outlines, the mission and each method's driven path.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/canvas.hpp"
#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::io {

struct DrivenPath {
    std::string label;
    std::vector<Pose2> poses;
};

/// `costmap` may be empty (no grid drawn). Objects are drawn at t = 0 with their ground-truth
/// affordance zones as `zones` defines them (the risk-time zones of the run). Throws FileError.
void write_nav_png(const std::filesystem::path& path, const sim::Scene& scene,
                   const Costmap& costmap, const std::vector<DrivenPath>& paths,
                   const std::vector<Eigen::Vector2d>& plan, const std::string& title,
                   const costmap::AffordanceParams& zones);

/// The costmap's colour for a cost (nullopt: free, not drawn), the same in every picture.
std::optional<Rgb> cost_colour(std::uint8_t cost);

/// A map built from recorded data (`makeway run`): the costmap, the objects with their zones, the
/// estimated trajectory, within `min_m`..`max_m`. Throws FileError.
void write_map_png(const std::filesystem::path& path, const Costmap& costmap,
                   const std::vector<ObjectEstimate>& objects,
                   const costmap::AffordanceParams& zones, const std::vector<Pose2>& trajectory,
                   const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
                   const std::string& title);

}  // namespace makeway::io
