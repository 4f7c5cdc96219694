#pragma once
// A user's own furniture: a folder of CAD meshes (OBJ/PLY/STL/DAE) with a class each, placed in
// makeway's object frame. `DIR/furniture.yaml` lists them with how their authors drew them:
//
//   furniture:
//     - {file: cafe_table.dae, class: table}                          # Collada: its own up axis
//     - {file: chairs/stacking.obj, class: chair, units: cm, up_axis: y, forward_axis: -z}
//     - {file: bench.stl, class: chair, units: mm, forward_axis: y, recentre: true}
//
// Without the index every mesh named chair_* or table_* is taken, Z-up, +x forward, in metres.
// The same keys place a mesh in a scene file. Every mesh is re-centred (footprint centre at the
// origin, lowest point on the floor) unless `recentre: false`.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/config_reader.hpp"
#include "io/mesh_io.hpp"
#include "makeway/common/mesh_placement.hpp"

namespace makeway::io {

/// The keys that place a user mesh, as written in a scene object or a furniture entry.
struct MeshPlacementKeys {
    std::string units = "m";
    double scale = 1.0;
    std::string up_axis = "z";
    std::string forward_axis = "x";
    bool recentre = true;
};
/// Reads the keys present in `s`.
void read_placement_keys(YamlSection& s, MeshPlacementKeys& keys);
/// The placement the keys say, or nullopt with every problem recorded in `s`.
std::optional<MeshPlacement> to_placement(const MeshPlacementKeys& keys, YamlSection& s);

using Warn = std::function<void(const std::string&)>;

/// read_mesh + place_mesh, and a warning (`what: mesh FILE: ...`) when the result cannot be a
/// piece of furniture of `cls`. Throws FileError naming the file.
TriangleMesh read_placed_mesh(const std::filesystem::path& file, const MeshPlacement& placement,
                              ObjectClass cls, const std::string& what, const Warn& warn,
                              const MeshReadLimits& limits = {});

struct FurnitureMesh {
    std::string name;  ///< the file's path in the folder, without extension
    ObjectClass cls = ObjectClass::kChair;
    std::shared_ptr<const TriangleMesh> mesh_object;
};

/// Every mesh of the folder (the index's order, or file names sorted). Throws FileError naming the
/// folder, the index (every problem) or the mesh; an index entry outside the folder is refused.
std::vector<FurnitureMesh> read_furniture_folder(const std::filesystem::path& dir,
                                                 const Warn& warn = {});

}  // namespace makeway::io
