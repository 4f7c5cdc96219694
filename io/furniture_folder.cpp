#include "io/furniture_folder.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/mesh_io.hpp"

namespace makeway::io {

void read_placement_keys(YamlSection& s, MeshPlacementKeys& k) {
    s.read("units", k.units);
    s.read("scale", k.scale);
    s.read("up_axis", k.up_axis);
    s.read("forward_axis", k.forward_axis);
    s.read("recentre", k.recentre);
}

std::optional<MeshPlacement> to_placement(const MeshPlacementKeys& k, YamlSection& s) {
    const auto up = parse_mesh_axis(k.up_axis), forward = parse_mesh_axis(k.forward_axis);
    const auto unit = parse_length_unit(k.units);
    bool ok = true;
    auto problem = [&](const std::string& m) { s.problem(m), ok = false; };
    if (!up) problem("up_axis must be x, y, z, -x, -y or -z (got '" + k.up_axis + "')");
    if (!forward)
        problem("forward_axis must be x, y, z, -x, -y or -z (got '" + k.forward_axis + "')");
    if (up && forward && !placement_rotation(*up, *forward))
        problem("up_axis and forward_axis are parallel");
    if (!unit) problem("units must be m, cm, mm, in or ft (got '" + k.units + "')");
    if (!(k.scale > 0.0) || !std::isfinite(k.scale)) problem("scale must be > 0");
    if (!ok) return std::nullopt;
    return MeshPlacement{*up, *forward, *unit * k.scale, k.recentre};
}

TriangleMesh read_placed_mesh(const std::filesystem::path& file, const MeshPlacement& placement,
                              ObjectClass cls, const std::string& what, const Warn& warn,
                              const MeshReadLimits& limits) {
    TriangleMesh mesh = place_mesh(read_mesh(file, limits), placement);
    if (const auto warning = implausible_furniture_extent(mesh, cls); warning && warn) {
        warn(what + ": mesh " + file.filename().string() + ": " + *warning);
    }
    return mesh;
}

namespace {

bool is_mesh_file(const std::filesystem::path& p) {
    const std::string ext = lower_extension(p);
    return ext == "obj" || ext == "ply" || ext == "stl" || ext == "dae";
}

std::vector<FurnitureMesh> read_index(const std::filesystem::path& dir,
                                      const std::filesystem::path& index, const Warn& warn) {
    YAML::Node root;
    try {
        root = load_yaml(read_file(index));
    } catch (const FormatError& e) {
        throw FileError(index.string(), e.what());
    }
    std::vector<std::string> problems;
    if (!root.IsMap()) throw FileError(index.string(), "must be a mapping with a 'furniture' list");
    YamlSection top(root, "", problems);
    const YAML::Node list = top.take("furniture");
    top.finish();
    if (!list || !list.IsSequence() || list.size() == 0)
        throw FileError(index.string(), "'furniture' must be a non-empty list");
    std::vector<FurnitureMesh> out;
    const std::filesystem::path root_dir = std::filesystem::weakly_canonical(dir);
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = "furniture[" + std::to_string(i) + "]";
        YamlSection s(list[i], name, problems);
        std::string file, cls_name;
        MeshPlacementKeys keys;
        s.read("file", file);
        s.read("class", cls_name);
        read_placement_keys(s, keys);
        s.finish();
        const auto cls = parse_object_class(cls_name);
        if (!cls) s.problem("class must be chair or table (got '" + cls_name + "')");
        const std::optional<MeshPlacement> placement = to_placement(keys, s);
        if (file.empty()) {
            s.problem("needs a file");
            continue;
        }
        const std::filesystem::path path = std::filesystem::weakly_canonical(dir / file);
        const auto rel = path.lexically_relative(root_dir);
        if (std::filesystem::path(file).is_absolute() || rel.empty() || *rel.begin() == "..") {
            s.problem("file '" + file + "' is outside the folder");
            continue;
        }
        if (!cls || !placement) continue;
        try {
            auto mesh = std::make_shared<TriangleMesh>(
                read_placed_mesh(dir / file, *placement, *cls, index.string() + ": " + name, warn));
            out.push_back({std::filesystem::path(file).replace_extension().generic_string(), *cls,
                           std::move(mesh)});
        } catch (const FileError& e) {
            s.problem(std::string("mesh ") + e.what());
        }
    }
    if (!problems.empty()) throw FileError(index.string(), join_problems(problems));
    return out;
}

}  // namespace

std::vector<FurnitureMesh> read_furniture_folder(const std::filesystem::path& dir,
                                                 const Warn& warn) {
    if (!std::filesystem::is_directory(dir))
        throw FileError(dir.string(), "not a folder of CAD meshes");
    const std::filesystem::path index = dir / "furniture.yaml";
    if (std::filesystem::exists(index)) return read_index(dir, index, warn);
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.is_regular_file() && is_mesh_file(e.path())) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    std::vector<FurnitureMesh> out;
    for (const auto& f : files) {
        const std::string name = f.stem().string();
        const auto cls = parse_object_class(name.substr(0, name.find('_')));
        if (!cls)
            throw FileError(f.string(),
                            "CAD file names must start with chair_ or table_ (or list the files in "
                            "furniture.yaml)");
        out.push_back({name, *cls,
                       std::make_shared<TriangleMesh>(
                           read_placed_mesh(f, MeshPlacement{}, *cls, dir.string(), warn))});
    }
    if (out.empty())
        throw FileError(dir.string(), "no CAD meshes (.obj, .ply, .stl, .dae) in the folder");
    return out;
}

}  // namespace makeway::io
