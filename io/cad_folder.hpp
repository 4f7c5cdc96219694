#pragma once
// A folder of CAD meshes as a verification library: every mesh's class from its file name
// (chair_*.obj, table_*.ply, ...), as a deployment keeps the models of its room's furniture.
#include <filesystem>

#include "makeway/verification/cad_library.hpp"

namespace makeway::io {

/// Throws FileError naming the folder or file: not a folder, a mesh not named chair_/table_, a
/// mesh that cannot be read, or no mesh at all.
verification::CadLibrary read_cad_folder(const std::filesystem::path& dir);

}  // namespace makeway::io
