#include "makeway/eval/scene_cad.hpp"

#include <set>
#include <string>

#include "makeway/sim/furniture.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::eval {

verification::CadLibrary default_cad_library() {
    verification::CadLibrary lib;
    for (ObjectClass cls : kAllObjectClasses) {
        for (sim::FurnitureStyle s : sim::scene_styles_of(cls))
            lib.add(std::string(sim::to_string(s)), cls, sim::make_furniture(s, 0).mesh_object);
    }
    return lib;
}

verification::CadLibrary scene_cad_library(const sim::Scene& scene) {
    verification::CadLibrary lib;
    std::set<std::string> added;
    for (const sim::SceneObject& o : scene.objects) {
        const std::string name = o.style.empty() ? o.mesh_file + "@" + std::to_string(o.scale)
                                                 : o.style + "_" + std::to_string(o.model_seed);
        if (added.insert(name).second) lib.add(name, o.cls, sim::model_of(o).mesh_object);
    }
    return lib;
}

}  // namespace makeway::eval
