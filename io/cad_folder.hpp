#pragma once
// A folder of CAD meshes as a verification library, as a deployment keeps the models of its room's
// furniture: every mesh's class from its file name (chair_*.obj, table_*.ply, ...) or from the
// folder's furniture.yaml, which also says how each was drawn (io/furniture_folder.hpp).
#include <filesystem>

#include "makeway/verification/cad_library.hpp"

namespace makeway::io {

/// Throws FileError naming the folder or file: not a folder, a mesh not named chair_/table_
/// (without an index), a bad index, a mesh that cannot be read, or no mesh at all. A mesh whose
/// size cannot be furniture of its class is a warning on stderr.
verification::CadLibrary read_cad_folder(const std::filesystem::path& dir);

}  // namespace makeway::io
