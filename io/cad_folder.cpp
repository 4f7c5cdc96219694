#include "io/cad_folder.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/mesh_io.hpp"

namespace makeway::io {

verification::CadLibrary read_cad_folder(const std::filesystem::path& dir) {
    if (!std::filesystem::is_directory(dir)) throw FileError(dir.string(), "not a folder of CAD meshes");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string ext = lower_extension(e.path());
        if (e.is_regular_file() && (ext == "obj" || ext == "ply" || ext == "stl" || ext == "dae")) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    verification::CadLibrary lib;
    for (const auto& f : files) {
        const std::string name = f.stem().string();
        const auto cls = parse_object_class(name.substr(0, name.find('_')));
        if (!cls) throw FileError(f.string(), "CAD file names must start with chair_ or table_");
        lib.add(name, *cls, read_mesh(f));
    }
    if (lib.models().empty()) throw FileError(dir.string(), "no CAD meshes (.obj, .ply, .stl, .dae) in the folder");
    return lib;
}

}  // namespace makeway::io
