// makeway cad / makeway scene: CAD models and procedural scenes.
#include <iostream>

#include "apps/commands.hpp"
#include "apps/recording.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/mesh_io.hpp"
#include "io/scene_io.hpp"
#include "io/scene_png.hpp"
#include "io/staged_output.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::apps {

int run_cad(const CadOptions& options) {
    const auto style = sim::parse_furniture_style(options.style);
    if (!style) throw io::FileError(options.out, "unknown style '" + options.style + "'");
    const sim::FurnitureModel m = sim::make_furniture(*style, options.seed);
    io::write_mesh(options.out, m.mesh_object);
    const Eigen::Vector3d s = m.box_object.size_m;
    std::cout << "wrote " << options.out << ": " << options.style << " seed " << options.seed
              << ", " << m.mesh_object.num_triangles() << " triangles, " << s.x() << " x " << s.y()
              << " x " << s.z() << " m (length x width x height)\n";
    return 0;
}

int run_scene(const SceneOptions& options) {
    sim::SceneGenParams p;
    p.seed = options.seed;
    p.density = *sim::parse_density(options.density);
    p.layout = *sim::parse_layout(options.layout);
    p.people = !options.no_people;
    const std::filesystem::path out = options.out;
    if (io::lower_extension(out) != "yaml" && io::lower_extension(out) != "yml") {
        throw io::FileError(out.string(), "a scene file must end in .yaml");
    }
    sim::Scene base;
    try {
        base = sim::generate_scene(p);
    } catch (const std::runtime_error& e) {
        throw io::FileError(out.string(), e.what());
    }
    // Every session's scene and picture, or none of them.
    io::StagedOutput staged(out.parent_path());
    std::vector<std::string> lines{
        "wrote " + out.string() + " and its picture (" +
        write_scene_with_picture(staged.staging() / out.filename(), base) + ")"};
    for (int k = 1; k < options.sessions; ++k) {
        const std::string name =
            out.stem().string() + "_session" + std::to_string(k) + out.extension().string();
        lines.push_back(
            "wrote " + (out.parent_path() / name).string() + " (" +
            write_scene_with_picture(staged.staging() / name, sim::make_session(base, k)) + ")");
    }
    staged.commit();
    for (const auto& line : lines) std::cout << line << "\n";
    return 0;
}

}  // namespace makeway::apps
