#include "makeway/eval/scene_cad.hpp"

#include <cstdint>
#include <set>
#include <string>

#include "makeway/common/random.hpp"
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

const NameTable<CadFit>& cad_fits_by_name() {
    static const NameTable<CadFit> kNames{
        {"exact", CadFit::kExact},
        {"scaled", CadFit::kScaled},
        {"other-dimensions", CadFit::kOtherDimensions},
    };
    return kNames;
}

std::string_view to_string(CadFit fit) { return name_in(cad_fits_by_name(), fit); }

std::optional<CadFit> parse_cad_fit(std::string_view name) {
    return value_named(cad_fits_by_name(), name);
}

verification::CadLibrary scene_cad_library(const sim::Scene& scene, CadFit fit) {
    verification::CadLibrary lib;
    std::set<std::string> added;
    for (const sim::SceneObject& o : scene.objects) {
        const std::string name = o.style.empty() ? o.mesh_file + "@" + std::to_string(o.scale)
                                                 : o.style + "_" + std::to_string(o.model_seed);
        if (!added.insert(name).second) continue;
        sim::SceneObject model = o;
        if (fit == CadFit::kOtherDimensions && !o.style.empty()) model.model_seed += 7919;
        TriangleMesh mesh = sim::model_of(model).mesh_object;
        if (fit == CadFit::kScaled || (fit == CadFit::kOtherDimensions && o.style.empty())) {
            // Seeded by the model's name (FNV-1a: the same on every platform, unlike std::hash).
            std::uint64_t seed = 1469598103934665603ULL;
            for (const char c : name)
                seed = (seed ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
            Rng rng = make_rng(seed, 77);
            const Eigen::Vector3f scale(static_cast<float>(uniform(rng, 0.9, 1.1)),
                                        static_cast<float>(uniform(rng, 0.9, 1.1)),
                                        static_cast<float>(uniform(rng, 0.9, 1.1)));
            for (Eigen::Vector3f& v : mesh.vertices_m) v = v.cwiseProduct(scale);
        }
        lib.add(name, o.cls, std::move(mesh));
    }
    return lib;
}

}  // namespace makeway::eval
