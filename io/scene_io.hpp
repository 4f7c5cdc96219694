#pragma once
// Scenes as YAML files a person can read and edit (see README "Scene files"). User meshes named in
// a scene are loaded relative to the scene file. Reads list every problem at once.
#include <filesystem>
#include <string>

#include "makeway/sim/scene.hpp"

namespace makeway::io {

/// Throws FileError ("PATH: 2 problems: ...") on any problem, including unreadable user meshes.
sim::Scene read_scene(const std::filesystem::path& path);
/// Throws FormatError. User meshes are not loaded (mesh_base_dir empty) or loaded from it.
sim::Scene parse_scene(std::string_view yaml_text, const std::filesystem::path& mesh_base_dir = {});

/// Atomic write.
void write_scene(const std::filesystem::path& path, const sim::Scene& scene);
std::string scene_to_yaml(const sim::Scene& scene);

}  // namespace makeway::io
