#include "io/zones_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/canvas.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::io {
namespace {

constexpr const char* kFormat = "makeway_zones";

// Default footprints for pictures of a zone learned without sizes.
Eigen::Vector2d picture_size(const costmap::ClassZone* z, ObjectClass cls) {
    if (z != nullptr && (z->typical_size_m.array() > 0.0).all()) return z->typical_size_m;
    return cls == ObjectClass::kChair ? Eigen::Vector2d(0.55, 0.55) : Eigen::Vector2d(1.6, 0.8);
}

void read_class(YamlSection& root, const char* name, std::optional<costmap::ClassZone>& out,
                std::vector<std::string>& problems) {
    if (!root.has(name)) return;
    const YAML::Node node = root.take(name);
    costmap::ClassZone z;
    YamlSection s(node, name, problems);
    s.read("observations", z.observations);
    s.read("typical_size_m", z.typical_size_m);
    const YAML::Node motions = s.take("motions");
    const bool given = motions && !motions.IsNull();
    if (given && !motions.IsSequence())
        s.problem("motions must be a list of [dx_m, dy_m, dyaw_deg, weight]");
    if (given && motions.IsSequence()) {
        for (std::size_t i = 0; i < motions.size(); ++i) {
            std::vector<double> v;
            try {
                v = motions[i].as<std::vector<double>>();
            } catch (const YAML::Exception&) {
            }
            if (v.size() != 4) {
                s.problem("motions[" + std::to_string(i) +
                          "] must be [dx_m, dy_m, dyaw_deg, weight]");
                break;
            }
            z.motions.push_back({v[0], v[1], deg_to_rad(v[2]), v[3]});
        }
    }
    s.finish();
    out = std::move(z);
}

}  // namespace

costmap::LearnedZones read_zones(const std::filesystem::path& path) {
    const std::string text = read_file(path);
    YAML::Node root;
    try {
        root = load_yaml(text);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
    if (!root.IsMap())
        throw FileError(path.string(),
                        "not a zones file (a YAML mapping with format: makeway_zones)");
    std::vector<std::string> problems;
    costmap::LearnedZones z;
    {
        YamlSection s(root, "", problems);
        std::string format;
        int version = 0;
        s.read("format", format);
        s.read("version", version);
        if (format != kFormat)
            s.problem(std::string("format must be ") + kFormat + " (got '" + format + "')");
        else if (version != 1)
            s.problem("version " + std::to_string(version) +
                      " is not known (this makeway reads 1)");
        s.read("kernel_m", z.kernel_m);
        s.read("coverage_threshold", z.coverage_threshold);
        s.read("prior_strength", z.prior_strength);
        read_class(s, "chair", z.chair, problems);
        read_class(s, "table", z.table, problems);
        s.finish();
    }
    if (problems.empty()) problems = z.validate();
    if (!problems.empty()) throw FileError(path.string(), join_problems(problems));
    return z;
}

std::shared_ptr<const costmap::LearnedZones> load_zones(const std::filesystem::path& path) {
    if (path.empty()) return nullptr;
    return std::make_shared<const costmap::LearnedZones>(read_zones(path));
}

void write_zones(const std::filesystem::path& path, const costmap::LearnedZones& zones,
                 const std::string& header) {
    YAML::Emitter out;
    out.SetDoublePrecision(6);
    out << YAML::BeginMap << YAML::Key << "format" << YAML::Value << kFormat << YAML::Key
        << "version" << YAML::Value << 1 << YAML::Key << "kernel_m" << YAML::Value << zones.kernel_m
        << YAML::Key << "coverage_threshold" << YAML::Value << zones.coverage_threshold << YAML::Key
        << "prior_strength" << YAML::Value << zones.prior_strength;
    for (const ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        const costmap::ClassZone* z = zones.of(cls);
        if (z == nullptr) continue;
        out << YAML::Key << std::string(to_string(cls)) << YAML::Value << YAML::BeginMap
            << YAML::Key << "observations" << YAML::Value << z->observations << YAML::Key
            << "typical_size_m" << YAML::Value << YAML::Flow << YAML::BeginSeq
            << z->typical_size_m.x() << z->typical_size_m.y() << YAML::EndSeq << YAML::Key
            << "motions" << YAML::Comment("[dx_m, dy_m, dyaw_deg, weight] in the object's frame")
            << YAML::Value << YAML::BeginSeq;
        for (const costmap::ZoneMotion& m : z->motions) {
            out << YAML::Flow << YAML::BeginSeq << m.dx_m << m.dy_m
                << std::round(rad_to_deg(m.dyaw_rad) * 1e4) / 1e4 << m.weight << YAML::EndSeq;
        }
        out << YAML::EndSeq << YAML::EndMap;
    }
    out << YAML::EndMap;
    std::ostringstream text;
    std::istringstream lines(header);
    for (std::string line; std::getline(lines, line);) text << "# " << line << "\n";
    text << out.c_str() << "\n";
    write_file_atomic(path, text.str());
}

void write_zones_png(const std::filesystem::path& path, const costmap::LearnedZones& zones,
                     const costmap::AffordanceParams& hand_drawn) {
    // Two panels side by side, each object at its own origin; 3.2 m between the panels' centres.
    constexpr double kHalf = 2.2, kGap = 4.6, kResolution = 0.02;
    Canvas canvas(Eigen::Vector2d(-kHalf, -kHalf), Eigen::Vector2d(kGap + kHalf, kHalf + 0.4),
                  120.0, 0.1);
    costmap::AffordanceParams learned = hand_drawn;
    learned.learned = std::make_shared<const costmap::LearnedZones>(zones);
    const Rgb learned_colour{0.85, 0.33, 0.10}, hand_colour{0.2, 0.2, 0.2},
        motion_colour{0.0, 0.35, 0.75};
    int panel = 0;
    for (const ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        const costmap::ClassZone* z = zones.of(cls);
        const Eigen::Vector2d origin(panel++ * kGap, 0.0);
        ObjectEstimate o;
        o.cls = cls;
        const Eigen::Vector2d size = picture_size(z, cls);
        o.box_world.centre_m << origin, 0.4;
        o.box_world.size_m << size, 0.8;
        // The zone's shading: darker where the footprint goes more often (1 - u).
        const int cells = static_cast<int>(2.0 * kHalf / kResolution);
        const Eigen::Vector2d corner = origin - Eigen::Vector2d(kHalf, kHalf);
        canvas.grid(corner, kResolution, cells, cells, [&](int x, int y) -> std::optional<Rgb> {
            const Eigen::Vector2d p = corner + kResolution * Eigen::Vector2d(x + 0.5, y + 0.5);
            const double u = costmap::zone_coordinate(o, learned, p);
            if (u > 1.0) return std::nullopt;
            const double a = 0.15 + 0.6 * (1.0 - u);
            return Rgb{1.0 - a * (1.0 - learned_colour[0]), 1.0 - a * (1.0 - learned_colour[1]),
                       1.0 - a * (1.0 - learned_colour[2])};
        });
        canvas.stroke_polyline(costmap::zone_outline(o, learned, 144), learned_colour, 2.0, true);
        canvas.stroke_polyline(costmap::zone_outline(o, hand_drawn, 144), hand_colour, 1.5, true,
                               true);
        const auto corners = o.box_world.bev_corners();
        canvas.stroke_polyline({corners.begin(), corners.end()}, {0, 0, 0}, 2.0, true);
        canvas.stroke_polyline({origin, origin + Eigen::Vector2d(0.5 * size.x() + 0.15, 0.0)},
                               {0, 0, 0}, 1.5);  // the facing
        double total = 0.0;
        if (z != nullptr)
            for (const costmap::ZoneMotion& m : z->motions) total += m.weight;
        if (z != nullptr && total > 0.0) {
            for (const costmap::ZoneMotion& m : z->motions) {
                canvas.dot(origin + Eigen::Vector2d(m.dx_m, m.dy_m),
                           std::clamp(40.0 * std::sqrt(m.weight / total), 2.0, 14.0),
                           motion_colour);
            }
        }
        std::ostringstream title;
        title << to_string(cls) << ": "
              << (z == nullptr ? std::string("hand-drawn (nothing learned)")
                               : std::to_string(static_cast<long>(std::lround(z->observations))) +
                                     " observed motions");
        canvas.text(origin + Eigen::Vector2d(-kHalf + 0.1, kHalf + 0.15), title.str(), 16.0,
                    {0, 0, 0});
    }
    canvas.text_px(10, canvas.height_px() - 30,
                   "solid: learned zone (shaded by how often the footprint goes there); dashed: "
                   "hand-drawn; dots: observed motions of the centre; object faces +x (right)",
                   13.0, {0.2, 0.2, 0.2});
    canvas.scale_bar();
    canvas.save_png(path);
}

}  // namespace makeway::io
