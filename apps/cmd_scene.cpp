// makeway cad / makeway scene: CAD models and procedural scenes.
#include <iostream>

#include "apps/command.hpp"
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

struct CadOptions {
    std::string style;
    std::uint64_t seed = 0;
    std::string out;
};

struct SceneOptions {
    std::uint64_t seed = 0;
    std::string density = "medium";
    std::string layout = "random";
    int sessions = 1;
    bool no_people = false;
    std::string usage = "default";
    std::string out = "scene.yaml";
};

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
    p.usage = *sim::parse_usage_profile(options.usage);
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

// The subcommands of this file, as --help lists them.
namespace {

void declare_cad(CommandSpec& c, CadOptions& o) {
    std::vector<std::string> styles;
    std::string names;
    for (int i = 0; i < makeway::sim::kNumFurnitureStyles; ++i) {
        styles.emplace_back(makeway::sim::to_string(static_cast<makeway::sim::FurnitureStyle>(i)));
        names += (i ? ", " : "") + styles.back();
    }
    c.option("--style", o.style, "One of " + names).required().choices(styles);
    c.option("--seed", o.seed, "Seed of the dimensions (real furniture ranges)").show_default();
    c.option("--out", o.out,
             "Mesh file (.obj, .ply, .stl); the object frame has its origin on the "
             "floor at the footprint centre, x forward, z up")
        .required();
}
const Registration<CadOptions> kCad{"cad", Group::kSimulation,
                                    "Write a procedural chair or table model (OBJ, PLY or STL)",
                                    declare_cad, run_cad};

void declare_scene(CommandSpec& c, SceneOptions& o) {
    c.option("--seed", o.seed, "Scene seed").show_default();
    c.option("--density", o.density, "Number of objects and clutter")
        .choices({"sparse", "medium", "dense"})
        .show_default();
    c.option("--layout", o.layout, "random, or study_space: one room with 12 tables and 22 chairs")
        .choices({"random", "study_space"})
        .show_default();
    c.option("--sessions", o.sessions,
             "Recording sessions of the same building with furniture moved "
             "between them; session k > 0 goes to NAME_sessionK.yaml")
        .range(1, 100)
        .show_default();
    c.flag("--no-people", o.no_people, "No walkers and no chair pushers");
    c.option("--usage", o.usage,
             "How people leave the furniture between sessions (README, usage profiles): "
             "default, pulled_back (chairs pulled straight back), sideways (chairs swung out to "
             "a side), tables_nudged (tables slid along their length with their chairs)")
        .choices(sim::usage_profile_names())
        .show_default();
    c.option("--out", o.out, "Scene file (.yaml)").show_default();
}
const Registration<SceneOptions> kScene{
    "scene", Group::kSimulation,
    "Generate an indoor scene (YAML) and its top-down picture (PNG "
    "beside it); every scene has a collision-free route start -> "
    "waypoint -> goal for the robot footprint",
    declare_scene, run_scene};

}  // namespace

}  // namespace makeway::apps
