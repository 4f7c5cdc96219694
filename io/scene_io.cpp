#include "io/scene_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <iomanip>
#include <memory>
#include <sstream>

#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/furniture_folder.hpp"
#include "io/mesh_io.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::io {
namespace {

void read_pose(YamlSection& parent, const char* key, Pose2& pose,
               std::vector<std::string>& problems, const std::string& prefix) {
    YamlSection s(parent.take(key), prefix + "." + key, problems);
    s.read("x_m", pose.x_m);
    s.read("y_m", pose.y_m);
    s.read("yaw_rad", pose.yaw_rad);
    s.finish();
}

template <typename Fn>
void for_each_item(YAML::Node list, const std::string& name, std::vector<std::string>& problems,
                   Fn&& fn) {
    if (!list || list.IsNull()) return;
    if (!list.IsSequence()) {
        problems.push_back(name + ": must be a list");
        return;
    }
    for (std::size_t i = 0; i < list.size(); ++i) fn(list[i], name + "[" + std::to_string(i) + "]");
}

// True when `file` (relative to `base`) resolves, links followed, to a path inside `base`.
bool inside_folder(const std::filesystem::path& base, const std::filesystem::path& file) {
    if (file.is_absolute()) return false;
    std::error_code ec;
    const auto root = std::filesystem::weakly_canonical(base, ec);
    if (ec) return false;
    const auto resolved = std::filesystem::weakly_canonical(base / file, ec);
    if (ec) return false;
    const auto rel = resolved.lexically_relative(root);
    return !rel.empty() && *rel.begin() != "..";
}

// Whether a scene may read its mesh `file`: inside the scene's folder, or anywhere when the user
// allows it; else the problem is recorded.
bool may_read(YamlSection& s, const std::filesystem::path& base, const std::string& file,
              const SceneReadOptions& options) {
    if (options.allow_outside_paths || inside_folder(base, file)) return true;
    s.problem("mesh '" + file +
              "' is outside the scene's folder (--allow-outside-paths to read it)");
    return false;
}

sim::SceneObject read_object(const YAML::Node& node, const std::string& prefix,
                             std::vector<std::string>& problems,
                             const std::filesystem::path& mesh_base_dir,
                             const SceneReadOptions& options) {
    sim::SceneObject o;
    YamlSection s(node, prefix, problems);
    std::string cls = "chair";
    s.read("id", o.id);
    s.read("class", cls);
    s.read("style", o.style);
    s.read("model_seed", o.model_seed);
    s.read("mesh", o.mesh_file);
    MeshPlacementKeys keys;
    read_placement_keys(s, keys);
    s.read("table_id", o.table_id);
    read_pose(s, "pose", o.pose, problems, prefix);
    s.finish();
    const auto parsed = parse_object_class(cls);
    if (!parsed) s.problem("class must be chair or table (got '" + cls + "')");
    o.cls = parsed.value_or(ObjectClass::kChair);
    if (!o.style.empty()) {
        const auto style = sim::parse_furniture_style(o.style);
        if (!style) {
            s.problem("unknown style '" + o.style + "'");
        } else if (sim::class_of(*style) != o.cls) {
            s.problem("style '" + o.style + "' is not a " + cls);
        }
    }
    o.scale = keys.scale;
    o.units = keys.units;
    o.up_axis = keys.up_axis;
    o.forward_axis = keys.forward_axis;
    o.recentre = keys.recentre;
    const std::optional<MeshPlacement> placement = to_placement(keys, s);
    if (!o.mesh_file.empty() && !mesh_base_dir.empty() &&
        may_read(s, mesh_base_dir, o.mesh_file, options) && placement) {
        try {
            o.user_mesh = std::make_shared<TriangleMesh>(
                read_placed_mesh(mesh_base_dir / o.mesh_file, *placement, o.cls, prefix,
                                 options.warn, options.mesh_limits));
        } catch (const FileError& e) {
            s.problem(std::string("mesh ") + e.what());
        }
    }
    return o;
}

sim::EnvironmentMesh read_environment(const YAML::Node& node, const std::string& prefix,
                                      std::vector<std::string>& problems,
                                      const std::filesystem::path& mesh_base_dir,
                                      const SceneReadOptions& options) {
    sim::EnvironmentMesh e;
    YamlSection s(node, prefix, problems);
    s.read("mesh", e.mesh_file);
    MeshPlacementKeys keys;
    keys.recentre = false;  // a scan's own frame: its origin and its floor's height
    read_placement_keys(s, keys);
    {
        YamlSection ps(s.take("pose"), prefix + ".pose", problems);
        ps.read("x_m", e.position_m.x());
        ps.read("y_m", e.position_m.y());
        ps.read("z_m", e.position_m.z());
        ps.read("roll_rad", e.rpy_rad.x());
        ps.read("pitch_rad", e.rpy_rad.y());
        ps.read("yaw_rad", e.rpy_rad.z());
        ps.finish();
    }
    s.finish();
    if (e.mesh_file.empty()) s.problem("mesh: required (the environment's mesh file)");
    if (!e.position_m.allFinite() || !e.rpy_rad.allFinite())
        s.problem("pose: every value must be a finite number");
    e.scale = keys.scale;
    e.units = keys.units;
    e.up_axis = keys.up_axis;
    e.forward_axis = keys.forward_axis;
    e.recentre = keys.recentre;
    const std::optional<MeshPlacement> placement = to_placement(keys, s);
    if (e.mesh_file.empty() || mesh_base_dir.empty()) return e;
    if (may_read(s, mesh_base_dir, e.mesh_file, options) && placement && e.position_m.allFinite() &&
        e.rpy_rad.allFinite()) {
        try {
            TriangleMesh mesh =
                place_mesh(read_mesh(mesh_base_dir / e.mesh_file, options.mesh_limits), *placement);
            sim::transform_mesh(
                mesh, make_T_xyz_rpy(e.position_m, e.rpy_rad.x(), e.rpy_rad.y(), e.rpy_rad.z()));
            e.mesh_world = std::make_shared<TriangleMesh>(std::move(mesh));
        } catch (const FileError& err) {
            s.problem(std::string("mesh ") + err.what());
        }
    }
    return e;
}

}  // namespace

sim::Scene parse_scene(std::string_view yaml_text, const std::filesystem::path& mesh_base_dir,
                       const SceneReadOptions& options) {
    const YAML::Node root = load_yaml(yaml_text);
    if (!root.IsMap()) throw FormatError("a scene must be a mapping (name, walls, objects, ...)");
    std::vector<std::string> problems;
    sim::Scene scene;
    YamlSection s(root, "scene", problems);
    s.read("name", scene.name);
    s.read("seed", scene.seed);
    s.read("density", scene.density);
    if (s.has("usage")) {
        std::string usage;
        s.read("usage", usage);
        if (const auto u = sim::parse_usage_profile(usage))
            scene.usage = *u;
        else
            s.problem("usage must be " + join_alternatives(sim::usage_profile_names()) + " (got '" +
                      usage + "')");
    }
    s.read("ceiling_height_m", scene.ceiling_height_m);
    {
        YamlSection floor(s.take("floor"), "floor", problems);
        floor.read("min_m", scene.floor_min_m);
        floor.read("max_m", scene.floor_max_m);
        floor.finish();
    }
    read_pose(s, "start", scene.start, problems, "scene");
    read_pose(s, "waypoint", scene.waypoint, problems, "scene");
    read_pose(s, "goal", scene.goal, problems, "scene");
    for_each_item(s.take("walls"), "walls", problems,
                  [&](const YAML::Node& n, const std::string& name) {
                      sim::Wall w;
                      YamlSection ws(n, name, problems);
                      ws.read("a_m", w.a_m);
                      ws.read("b_m", w.b_m);
                      ws.read("thickness_m", w.thickness_m);
                      ws.read("height_m", w.height_m);
                      ws.finish();
                      scene.walls.push_back(w);
                  });
    for_each_item(s.take("pillars"), "pillars", problems,
                  [&](const YAML::Node& n, const std::string& name) {
                      sim::Pillar p;
                      YamlSection ps(n, name, problems);
                      ps.read("centre_m", p.centre_m);
                      ps.read("size_m", p.size_m);
                      ps.read("height_m", p.height_m);
                      ps.finish();
                      scene.pillars.push_back(p);
                  });
    for_each_item(s.take("environment"), "environment", problems,
                  [&](const YAML::Node& n, const std::string& name) {
                      scene.environment.push_back(
                          read_environment(n, name, problems, mesh_base_dir, options));
                  });
    for_each_item(
        s.take("objects"), "objects", problems, [&](const YAML::Node& n, const std::string& name) {
            scene.objects.push_back(read_object(n, name, problems, mesh_base_dir, options));
        });
    for_each_item(
        s.take("walkers"), "walkers", problems, [&](const YAML::Node& n, const std::string& name) {
            sim::Walker w;
            YamlSection ws(n, name, problems);
            ws.read("speed_mps", w.speed_mps);
            ws.read("phase_s", w.phase_s);
            for_each_item(ws.take("route_m"), name + ".route_m", problems,
                          [&](const YAML::Node& p, const std::string& pn) {
                              try {
                                  if (!p.IsSequence() || p.size() != 2)
                                      throw YAML::Exception(YAML::Mark::null_mark(), "");
                                  w.route_m.emplace_back(p[0].as<double>(), p[1].as<double>());
                              } catch (const YAML::Exception&) {
                                  problems.push_back(pn + ": must be a pair of numbers [x, y]");
                              }
                          });
            ws.finish();
            scene.walkers.push_back(w);
        });
    for_each_item(s.take("pushers"), "pushers", problems,
                  [&](const YAML::Node& n, const std::string& name) {
                      sim::ChairPusher p;
                      YamlSection ps(n, name, problems);
                      ps.read("chair_id", p.chair_id);
                      ps.read("period_s", p.period_s);
                      ps.read("pull_m", p.pull_m);
                      ps.read("phase_s", p.phase_s);
                      ps.finish();
                      scene.pushers.push_back(p);
                  });
    s.finish();
    for (const auto& m : scene.validate()) problems.push_back(m);
    if (!problems.empty()) throw FormatError(join_problems(problems));
    return scene;
}

sim::Scene read_scene(const std::filesystem::path& path, const SceneReadOptions& options) {
    const std::string text = read_file(path);
    try {
        std::filesystem::path base = path.parent_path();
        if (base.empty()) base = ".";
        return parse_scene(text, base, options);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

std::string scene_to_yaml(const sim::Scene& scene) {
    YAML::Emitter out;
    out.SetDoublePrecision(17);
    auto pose = [&](const char* key, const Pose2& p) {
        out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "x_m"
            << YAML::Value << p.x_m << YAML::Key << "y_m" << YAML::Value << p.y_m << YAML::Key
            << "yaw_rad" << YAML::Value << p.yaw_rad << YAML::EndMap;
    };
    auto vec2 = [&](const char* key, const Eigen::Vector2d& v) {
        out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v.x() << v.y()
            << YAML::EndSeq;
    };
    out << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << scene.name;
    out << YAML::Key << "seed" << YAML::Value << scene.seed;
    out << YAML::Key << "density" << YAML::Value << scene.density;
    if (scene.usage != sim::UsageProfile::kDefault)  // how sessions move the furniture
        out << YAML::Key << "usage" << YAML::Value << std::string(sim::to_string(scene.usage));
    out << YAML::Key << "ceiling_height_m" << YAML::Value << scene.ceiling_height_m;
    out << YAML::Key << "floor" << YAML::Value << YAML::BeginMap;
    vec2("min_m", scene.floor_min_m);
    vec2("max_m", scene.floor_max_m);
    out << YAML::EndMap;
    pose("start", scene.start);
    pose("waypoint", scene.waypoint);
    pose("goal", scene.goal);
    out << YAML::Key << "walls" << YAML::Value << YAML::BeginSeq;
    for (const auto& w : scene.walls) {
        out << YAML::Flow << YAML::BeginMap;
        vec2("a_m", w.a_m);
        vec2("b_m", w.b_m);
        out << YAML::Key << "thickness_m" << YAML::Value << w.thickness_m << YAML::Key << "height_m"
            << YAML::Value << w.height_m << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::Key << "pillars" << YAML::Value << YAML::BeginSeq;
    for (const auto& p : scene.pillars) {
        out << YAML::Flow << YAML::BeginMap;
        vec2("centre_m", p.centre_m);
        vec2("size_m", p.size_m);
        out << YAML::Key << "height_m" << YAML::Value << p.height_m << YAML::EndMap;
    }
    out << YAML::EndSeq;
    if (!scene.environment.empty()) {
        out << YAML::Key << "environment" << YAML::Value << YAML::BeginSeq;
        for (const auto& e : scene.environment) {
            out << YAML::Flow << YAML::BeginMap << YAML::Key << "mesh" << YAML::Value << e.mesh_file
                << YAML::Key << "scale" << YAML::Value << e.scale << YAML::Key << "units"
                << YAML::Value << e.units << YAML::Key << "up_axis" << YAML::Value << e.up_axis
                << YAML::Key << "forward_axis" << YAML::Value << e.forward_axis << YAML::Key
                << "recentre" << YAML::Value << e.recentre << YAML::Key << "pose" << YAML::Value
                << YAML::Flow << YAML::BeginMap;
            const char* keys[] = {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"};
            for (int i = 0; i < 6; ++i) {
                out << YAML::Key << keys[i] << YAML::Value
                    << (i < 3 ? e.position_m[i] : e.rpy_rad[i - 3]);
            }
            out << YAML::EndMap << YAML::EndMap;
        }
        out << YAML::EndSeq;
    }
    out << YAML::Key << "objects" << YAML::Value << YAML::BeginSeq;
    for (const auto& o : scene.objects) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "id" << YAML::Value << o.id << YAML::Key
            << "class" << YAML::Value << std::string(to_string(o.cls));
        if (o.mesh_file.empty()) {
            out << YAML::Key << "style" << YAML::Value << o.style << YAML::Key << "model_seed"
                << YAML::Value << o.model_seed;
        } else {
            out << YAML::Key << "mesh" << YAML::Value << o.mesh_file << YAML::Key << "scale"
                << YAML::Value << o.scale << YAML::Key << "units" << YAML::Value << o.units
                << YAML::Key << "up_axis" << YAML::Value << o.up_axis << YAML::Key << "forward_axis"
                << YAML::Value << o.forward_axis << YAML::Key << "recentre" << YAML::Value
                << o.recentre;
        }
        if (o.table_id) out << YAML::Key << "table_id" << YAML::Value << o.table_id;
        pose("pose", o.pose);
        out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::Key << "walkers" << YAML::Value << YAML::BeginSeq;
    for (const auto& w : scene.walkers) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "speed_mps" << YAML::Value
            << w.speed_mps << YAML::Key << "phase_s" << YAML::Value << w.phase_s << YAML::Key
            << "route_m" << YAML::Value << YAML::BeginSeq;
        for (const auto& p : w.route_m)
            out << YAML::Flow << YAML::BeginSeq << p.x() << p.y() << YAML::EndSeq;
        out << YAML::EndSeq << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::Key << "pushers" << YAML::Value << YAML::BeginSeq;
    for (const auto& p : scene.pushers) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "chair_id" << YAML::Value << p.chair_id
            << YAML::Key << "period_s" << YAML::Value << p.period_s << YAML::Key << "pull_m"
            << YAML::Value << p.pull_m << YAML::Key << "phase_s" << YAML::Value << p.phase_s
            << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
    return "# makeway scene: lengths in metres, angles in radians, poses are T_world_object.\n"
           "# Object styles: four_leg_chair office_chair stool armchair rect_table round_table\n"
           "# conference_table; or `mesh: FILE` (OBJ/PLY/STL/DAE, relative to this file) with "
           "`scale`, `units`\n"
           "# (m, cm, mm, in, ft), `up_axis` and `forward_axis` (x, y, z, -x, ...) and "
           "`recentre`.\n" +
           std::string(out.c_str()) + "\n";
}

void write_scene(const std::filesystem::path& path, const sim::Scene& scene) {
    write_file_atomic(path, scene_to_yaml(scene));
}

}  // namespace makeway::io
