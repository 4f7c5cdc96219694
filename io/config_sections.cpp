#include "io/config_sections.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "makeway/common/param_tables.hpp"
#include "makeway/costmap/param_tables.hpp"
#include "makeway/labelling/param_tables.hpp"
#include "makeway/odometry/param_tables.hpp"
#include "makeway/pipeline/param_tables.hpp"
#include "makeway/planning/param_tables.hpp"
#include "makeway/tracking/param_tables.hpp"
#include "makeway/verification/param_tables.hpp"

namespace makeway::io {
namespace {

using pipeline::NavigatorParams;
using pipeline::SystemParams;

// Sections that gather more than one stage's table; a stage's own keys stay in its table.
const ParamTable<SystemParams>& lidar_odometry_section() {
    static const ParamTable<SystemParams> t = [] {
        ParamTable<SystemParams> s;
        s.add("enabled", &SystemParams::lidar_odometry_enabled, "false: the wheel odometry alone")
            .include(
                "", [](SystemParams& p) -> odometry::OdometryParams& { return p.lidar_odometry; },
                odometry::odometry_table());
        return s;
    }();
    return t;
}

const ParamTable<SystemParams>& verification_section() {
    static const ParamTable<SystemParams> t = [] {
        ParamTable<SystemParams> s;
        s.add("enabled", &SystemParams::verification_enabled,
              "false: detections are not checked against CAD models")
            .include(
                "", [](SystemParams& p) -> verification::VerifyParams& { return p.verify; },
                verification::verify_table())
            .include(
                "shape_", [](SystemParams& p) -> pipeline::TrackedShapeParams& { return p.shapes; },
                pipeline::tracked_shape_table())
            .include(
                "back_yaw_",
                [](SystemParams& p) -> verification::BackYawParams& { return p.back_yaw; },
                verification::back_yaw_table());
        return s;
    }();
    return t;
}

const ParamTable<NavigatorParams>& costmap_section() {
    static const ParamTable<NavigatorParams> t = [] {
        ParamTable<NavigatorParams> s;
        s.include(
             "", [](NavigatorParams& n) -> costmap::ObstacleLayerParams& { return n.obstacle; },
             costmap::obstacle_layer_table())
            .include(
                "inflation_",
                [](NavigatorParams& n) -> costmap::InflationParams& { return n.inflation; },
                costmap::inflation_table());
        return s;
    }();
    return t;
}

const ParamTable<NavigatorParams>& planning_section() {
    static const ParamTable<NavigatorParams> t = [] {
        ParamTable<NavigatorParams> s;
        s.include(
             "astar_", [](NavigatorParams& n) -> planning::AStarParams& { return n.astar; },
             planning::astar_table())
            .include(
                "dwa_", [](NavigatorParams& n) -> planning::DwaParams& { return n.dwa; },
                planning::dwa_table())
            .include(
                "", [](NavigatorParams& n) -> NavigatorParams& { return n; },
                pipeline::navigator_policy_table());
        return s;
    }();
    return t;
}

// Reads one key into its value (the YamlSection names the problems).
void read_param(YamlSection& s, const char* key, const BoundParam& p) {
    if (auto* const* d = std::get_if<double*>(&p.ref)) {
        p.range.infinity ? s.read_or_infinity(key, **d) : s.read(key, **d);
    } else if (auto* const* i = std::get_if<int*>(&p.ref)) {
        s.read(key, **i);
    } else if (auto* const* u = std::get_if<std::uint32_t*>(&p.ref)) {
        s.read(key, **u);
    } else if (auto* const* w = std::get_if<std::uint64_t*>(&p.ref)) {
        s.read(key, **w);
    } else if (auto* const* b = std::get_if<bool*>(&p.ref)) {
        s.read(key, **b);
    } else if (const auto* c = std::get_if<ParamChoice>(&p.ref)) {
        const YAML::Node v = s.take(key);
        if (!v || v.IsNull()) return;
        const std::string list = join_alternatives(c->names);
        std::vector<std::string> chosen;
        bool ok = c->list ? v.IsSequence() && v.size() > 0 : v.IsScalar();
        std::string got;
        if (ok && c->list) {
            for (const auto& item : v) chosen.push_back(item.IsScalar() ? item.Scalar() : "?");
        } else if (ok) {
            chosen.push_back(v.Scalar());
        }
        for (const std::string& n : chosen) {
            if (std::find(c->names.begin(), c->names.end(), n) == c->names.end()) {
                ok = false;
                got = n;
            }
        }
        if (!ok) {
            s.add_validation(
                {std::string(key) +
                 (c->list ? ": must be a list of " + list + " (e.g. [" + c->names.front() + "])"
                          : ": must be " + list) +
                 (got.empty() ? "" : " (got '" + got + "')")});
            return;
        }
        c->set(chosen);
    }
}

std::string value_text(const BoundParam& p) {
    if (auto* const* d = std::get_if<double*>(&p.ref)) {
        const std::string t = param_number(**d);
        return std::isfinite(**d) && t.find_first_of(".e") == std::string::npos ? t + ".0" : t;
    }
    if (auto* const* i = std::get_if<int*>(&p.ref)) return std::to_string(**i);
    if (auto* const* u = std::get_if<std::uint32_t*>(&p.ref)) return std::to_string(**u);
    if (auto* const* w = std::get_if<std::uint64_t*>(&p.ref)) return std::to_string(**w);
    if (auto* const* b = std::get_if<bool*>(&p.ref)) return **b ? "true" : "false";
    const auto& c = std::get<ParamChoice>(p.ref);
    const std::vector<std::string> v = c.get();
    if (!c.list) return v.empty() ? std::string() : v.front();
    std::string out = "[";
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i];
    return out + "]";
}

std::string range_text(const BoundParam& p) {
    if (std::holds_alternative<bool*>(p.ref)) return "true | false";
    if (const auto* c = std::get_if<ParamChoice>(&p.ref)) {
        std::string out = c->list ? "list of " : "";
        for (std::size_t i = 0; i < c->names.size(); ++i) out += (i ? " | " : "") + c->names[i];
        return out;
    }
    return p.range.text();
}

// "  key: value" padded to the comment column, then "# doc".
void write_line(std::ostringstream& out, const std::string& text, const std::string& doc) {
    out << text;
    if (!doc.empty())
        out << std::string(text.size() < 30 ? 30 - text.size() : 1, ' ') << "# " << doc;
    out << "\n";
}

}  // namespace

std::vector<BoundSection> config_sections(Config& c) {
    SystemParams& sys = c.system;
    std::vector<BoundSection> s;
    s.push_back(bind_section("robot", "Clearpath Jackal", robot_description_table(), c.robot,
                             "The robot, described once (common/robot_description.hpp): the "
                             "simulator drives it, and the\n"
                             "online system's costmap, DWA and collision monitor plan and guard "
                             "for it (pipeline::apply_robot)."));
    s.push_back(bind_section(
        "affordance", "object-aware costmap zones (also the risk-time zones of the benchmark)",
        costmap::affordance_table(), c.affordance));
    s.push_back(bind_section(
        "lidar_odometry",
        "the pose of every sweep: registration against a local voxel map, wheels as prior",
        lidar_odometry_section(), sys,
        "The online system (src/makeway/pipeline): what `ours` runs in the demo, navigate and "
        "bench nav."));
    s.push_back(bind_section("perception",
                             "front end: keyframes, ground plane, ground and ceiling removal",
                             pipeline::keyframe_table(), sys.keyframe));
    s.push_back(bind_section("verification",
                             "4-DoF point-to-plane ICP against the room's CAD models",
                             verification_section(), sys));
    s.push_back(bind_section("tracking", "the object map", tracking::tracker_table(), sys.tracker));
    s.push_back(bind_section(
        "costmap", "the obstacle and inflation layers (the robot's body and radii from robot:)",
        costmap_section(), sys.navigator));
    s.push_back(bind_section("planning", "A*, DWA and the policy around them", planning_section(),
                             sys.navigator));
    s.push_back(bind_section("collision_monitor",
                             "between the navigator and the motors, on the raw sweep (nav2's "
                             "collision_monitor); footprint, body and "
                             "braking from robot:",
                             planning::collision_monitor_table(), sys.navigator.monitor));
    s.push_back(bind_section("labelling",
                             "makeway label: the automatic annotation of multi-session drives",
                             labelling::label_table(), c.labelling));
    return s;
}

void read_sections(const YAML::Node& root, std::vector<BoundSection>& sections,
                   std::vector<std::string>& problems, std::vector<std::string>& deprecated) {
    for (BoundSection& sec : sections) {
        const bool old = !sec.old_name.empty() && root.IsMap() && root[sec.old_name];
        if (old && root[sec.name]) {
            problems.push_back(sec.old_name + " and " + sec.name + ": both given (" + sec.old_name +
                               " is " + sec.name + "'s old name)");
            continue;
        }
        if (old)
            deprecated.push_back(sec.old_name + ": the section is deprecated: it is now " +
                                 sec.name);
        YamlSection s(root[old ? sec.old_name : sec.name], old ? sec.old_name : sec.name, problems);
        // Keys "group.key" live in the nested mapping `group`, read after the section's own keys.
        std::vector<std::string> groups;
        for (const BoundParam& p : sec.params) {
            const std::size_t dot = p.key.find('.');
            if (dot != std::string::npos) {
                const std::string g = p.key.substr(0, dot);
                if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
                continue;
            }
            const bool has_new = s.has(p.key.c_str());
            if (!p.old_key.empty() && s.has(p.old_key.c_str())) {
                if (has_new) {
                    s.take(p.old_key.c_str());  // known, just not with its new name beside it
                    s.problem(p.old_key + " and " + p.key + " both given (" + p.old_key + " is " +
                              p.key + "'s old name)");
                } else {
                    read_param(s, p.old_key.c_str(), p);
                    deprecated.push_back(sec.name + "." + p.old_key + " is deprecated: it is now " +
                                         sec.name + "." + p.key);
                }
            }
            read_param(s, p.key.c_str(), p);
        }
        for (const std::string& g : groups) {
            YamlSection nested(s.take(g.c_str()), sec.name + "." + g, problems);
            for (const BoundParam& p : sec.params) {
                if (p.key.rfind(g + ".", 0) == 0)
                    read_param(nested, p.key.c_str() + g.size() + 1, p);
            }
            nested.finish();
        }
        s.finish();
        s.add_validation(sec.problems());
    }
}

std::string write_sections(const std::vector<BoundSection>& sections, const std::string& header) {
    std::ostringstream out;
    out << header;
    for (const BoundSection& sec : sections) {
        out << "\n";
        if (!sec.preface.empty()) {
            std::istringstream lines(sec.preface);
            for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
        }
        write_line(out, sec.name + ":", sec.doc);
        std::string group;
        for (const BoundParam& p : sec.params) {
            const std::size_t dot = p.key.find('.');
            const std::string g = dot == std::string::npos ? std::string() : p.key.substr(0, dot);
            if (!g.empty() && g != group) out << "  " << g << ":\n";
            group = g;
            const std::string indent = g.empty() ? "  " : "    ";
            write_line(out, indent + p.key.substr(g.empty() ? 0 : dot + 1) + ": " + value_text(p),
                       p.doc);
        }
    }
    return out.str();
}

std::string describe_sections(const std::vector<BoundSection>& sections) {
    std::ostringstream out;
    for (const BoundSection& sec : sections) {
        out << sec.name << ": " << sec.doc << "\n";
        for (const BoundParam& p : sec.params) {
            std::string line = "  " + p.key + " = " + value_text(p);
            line += std::string(line.size() < 44 ? 44 - line.size() : 1, ' ') + range_text(p);
            const std::string unit = param_unit(p.key);
            if (!unit.empty()) line += " [" + unit + "]";
            if (!p.doc.empty()) line += "  " + p.doc;
            if (!p.old_key.empty()) line += " (formerly " + p.old_key + ")";
            out << line << "\n";
        }
    }
    return out.str();
}

}  // namespace makeway::io
