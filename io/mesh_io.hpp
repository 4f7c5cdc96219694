#pragma once
// Triangle meshes through assimp: read OBJ, PLY, STL, DAE (and anything else assimp knows);
// write OBJ, PLY, STL (binary) atomically.
#include <filesystem>

#include "makeway/common/triangle_mesh.hpp"

namespace makeway::io {

/// Node transforms applied, polygons triangulated, points and lines dropped. Throws FileError when
/// the file is unreadable or holds no triangles.
TriangleMesh read_mesh(const std::filesystem::path& path);

/// Parses a mesh held in memory; `extension_hint` is e.g. "obj". Throws FormatError.
TriangleMesh parse_mesh(std::string_view bytes, const std::string& extension_hint);

/// Format from the extension (.obj, .ply, .stl). Throws FileError.
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace makeway::io
