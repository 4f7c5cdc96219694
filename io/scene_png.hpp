#pragma once
// Top-down picture of a scene: walls, pillars, furniture (mesh footprints and boxes with their
// heading), people and their routes, pulled-chair directions, the mission and the driven path.
#include <filesystem>
#include <string>
#include <vector>

#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::io {

struct ScenePicture {
    std::vector<Eigen::Vector2d> route_m;  ///< planned route (dashed)
    std::vector<Pose2> trajectory;         ///< driven path (solid)
    std::string title;
    double pixels_per_m = 40.0;
};

class Canvas;
/// The scene's walls and pillars, filled.
void draw_structure(Canvas& canvas, const sim::Scene& scene);

/// `models[i]` belongs to scene.objects[i]. Objects are drawn at t = 0. Throws FileError.
void write_scene_png(const std::filesystem::path& path, const sim::Scene& scene,
                     const std::vector<sim::ObjectModel>& models, const ScenePicture& picture = {});

}  // namespace makeway::io
