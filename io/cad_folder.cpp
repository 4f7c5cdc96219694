#include "io/cad_folder.hpp"

#include <iostream>

#include "io/furniture_folder.hpp"

namespace makeway::io {

verification::CadLibrary read_cad_folder(const std::filesystem::path& dir) {
    verification::CadLibrary lib;
    for (const FurnitureMesh& m : read_furniture_folder(dir, [](const std::string& w) { std::cerr << "makeway: warning: " << w << "\n"; })) {
        lib.add(m.name, m.cls, *m.mesh_object);
    }
    return lib;
}

}  // namespace makeway::io
