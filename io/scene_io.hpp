#pragma once
// Scenes as YAML files a person can read and edit (see README "Scene files"). User meshes named in
// a scene are loaded relative to the scene file. Reads list every problem at once.
#include <filesystem>
#include <functional>
#include <string>

#include "io/error.hpp"
#include "io/mesh_io.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::io {

struct SceneReadOptions {
    /// A scene names its meshes relative to its own folder and cannot reach outside it (`../x.obj`,
    /// absolute paths, links leading out): a scene file from elsewhere reads no other files.
    bool allow_outside_paths = false;
    /// Told what is readable but suspicious (a user mesh whose size cannot be furniture of its
    /// class); by default a line on stderr.
    std::function<void(const std::string&)> warn = print_warning;
    /// What each user mesh may cost its reader (a fuzzer's time limit is shorter than a user's).
    MeshReadLimits mesh_limits;
};

/// Throws FileError ("PATH: 2 problems: ...") on any problem, including unreadable user meshes.
sim::Scene read_scene(const std::filesystem::path& path, const SceneReadOptions& options = {});
/// Throws FormatError. User meshes are not loaded (mesh_base_dir empty) or loaded from it.
sim::Scene parse_scene(std::string_view yaml_text, const std::filesystem::path& mesh_base_dir = {},
                       const SceneReadOptions& options = {});

/// Atomic write.
void write_scene(const std::filesystem::path& path, const sim::Scene& scene);
std::string scene_to_yaml(const sim::Scene& scene);

}  // namespace makeway::io
