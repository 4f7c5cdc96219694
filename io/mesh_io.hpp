#pragma once
// Triangle meshes through assimp: read OBJ, PLY, STL, DAE (and anything else assimp knows);
// write OBJ, PLY, STL (binary) atomically.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "makeway/common/triangle_mesh.hpp"

namespace makeway::io {

/// What one mesh file may cost the reader (assimp, in a child process).
struct MeshReadLimits {
    std::size_t memory_bytes = std::size_t{4} << 30;
    double seconds = 60.0;
};

/// Node transforms applied, polygons triangulated, points and lines dropped. Throws FileError when
/// the file is unreadable or holds no triangles, or the reader exceeds `limits`.
TriangleMesh read_mesh(const std::filesystem::path& path, const MeshReadLimits& limits = {});

/// Parses a mesh held in memory; `extension_hint` is e.g. "obj". Throws FormatError, also when
/// the reader crashes, runs out of its memory or time on the file (it runs in a child process).
TriangleMesh parse_mesh(std::string_view bytes, const std::string& extension_hint,
                        const MeshReadLimits& limits = {});

/// Format from the extension (.obj, .ply, .stl). Throws FileError.
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace makeway::io
