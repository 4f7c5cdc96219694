#include "io/json_io.hpp"

#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace {

Eigen::Vector3d vec3_from(const Json& j, const char* key) {
    if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3) {
        throw FormatError(std::string("'") + key + "' must be an array of 3 numbers");
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
        if (!j[key][i].is_number())
            throw FormatError(std::string("'") + key + "' holds a non-number");
        v[i] = j[key][i].get<double>();
    }
    return v;
}

}  // namespace

void write_json(const std::filesystem::path& path, const Json& value) {
    write_file_atomic(path, dump_json(value, 2) + "\n");
}

std::string dump_json(const Json& value, int indent) {
    // Field names and paths come from files and command lines: bytes that are not UTF-8 are
    // replaced (U+FFFD) rather than ending the run in an internal error.
    return value.dump(indent, ' ', false, Json::error_handler_t::replace);
}

Json read_json(const std::filesystem::path& path) {
    const std::string text = read_file(path);
    try {
        return Json::parse(text);
    } catch (
        const Json::exception& e) {  // parse_error, and out_of_range for a number that overflows
        throw FileError(path.string(), std::string("invalid JSON: ") + e.what());
    }
}

Json to_json(const OrientedBox& box) {
    return {{"centre_m", {box.centre_m.x(), box.centre_m.y(), box.centre_m.z()}},
            {"size_m", {box.size_m.x(), box.size_m.y(), box.size_m.z()}},
            {"yaw_rad", box.yaw_rad}};
}

OrientedBox box_from_json(const Json& j) {
    if (!j.is_object()) throw FormatError("box must be an object");
    OrientedBox box;
    box.centre_m = vec3_from(j, "centre_m");
    box.size_m = vec3_from(j, "size_m");
    if (!j.contains("yaw_rad") || !j["yaw_rad"].is_number()) {
        throw FormatError("'yaw_rad' must be a number");
    }
    box.yaw_rad = j["yaw_rad"].get<double>();
    if (!box.is_valid()) throw FormatError("box has a non-finite value or a size <= 0");
    return box;
}

Json to_json(const PointBounds& b) {
    if (!b.valid) return nullptr;
    return {{"min", {b.min_m.x(), b.min_m.y(), b.min_m.z()}},
            {"max", {b.max_m.x(), b.max_m.y(), b.max_m.z()}}};
}

}  // namespace makeway::io

namespace makeway::io {

Json pose_to_json(const Isometry3& T) {
    const Eigen::Vector3d t = T.translation();
    const Eigen::Quaterniond q(T.linear());
    return {{"t_m", {t.x(), t.y(), t.z()}}, {"q_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

Isometry3 pose_from_json(const Json& j, const std::string& name) {
    const std::string form =
        "'" + name +
        "' must be {\"t_m\": [x, y, z], \"q_wxyz\": [w, x, y, z]} or {\"t_m\", \"yaw_rad\"}";
    if (!j.is_object() || !j.contains("t_m")) throw FormatError(form);
    Eigen::Vector3d t;
    try {
        t = vec3_from(j, "t_m");
    } catch (const FormatError&) {
        throw FormatError(form);
    }
    Isometry3 T = Isometry3::Identity();
    if (j.contains("q_wxyz")) {
        const Json& a = j["q_wxyz"];
        if (!a.is_array() || a.size() != 4) throw FormatError(form);
        Eigen::Vector4d c;
        for (int i = 0; i < 4; ++i) {
            if (!a[static_cast<std::size_t>(i)].is_number()) throw FormatError(form);
            c[i] = a[static_cast<std::size_t>(i)].get<double>();
        }
        if (!c.allFinite() || !t.allFinite())
            throw FormatError("'" + name + "' is NaN or infinite");
        if (std::abs(c.norm() - 1.0) > 1e-3)
            throw FormatError("'" + name + ".q_wxyz' is not a unit quaternion");
        T.linear() = Eigen::Quaterniond(c[0], c[1], c[2], c[3]).normalized().toRotationMatrix();
        T.translation() = t;
        return T;
    }
    if (!j.contains("yaw_rad") || !j["yaw_rad"].is_number()) throw FormatError(form);
    const double yaw = j["yaw_rad"].get<double>();
    if (!t.allFinite() || !std::isfinite(yaw))
        throw FormatError("'" + name + "' is NaN or infinite");
    return make_T_xyz_yaw(t, yaw);
}

}  // namespace makeway::io
