#include "io/cad_folder.hpp"

#include "io/error.hpp"
#include "io/furniture_folder.hpp"

namespace makeway::io {

verification::CadLibrary read_cad_folder(const std::filesystem::path& dir) {
    verification::CadLibrary lib;
    for (const FurnitureMesh& m : read_furniture_folder(dir, print_warning)) {
        lib.add(m.name, m.cls, *m.mesh_object);
    }
    return lib;
}

}  // namespace makeway::io
