#include "makeway/common/mesh_placement.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace makeway {

std::optional<MeshAxis> parse_mesh_axis(std::string_view name) {
    std::string s;
    for (char c : name) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (s == "x" || s == "+x") return MeshAxis::kPosX;
    if (s == "-x") return MeshAxis::kNegX;
    if (s == "y" || s == "+y") return MeshAxis::kPosY;
    if (s == "-y") return MeshAxis::kNegY;
    if (s == "z" || s == "+z") return MeshAxis::kPosZ;
    if (s == "-z") return MeshAxis::kNegZ;
    return std::nullopt;
}

std::string_view to_string(MeshAxis axis) {
    switch (axis) {
        case MeshAxis::kPosX:
            return "+x";
        case MeshAxis::kNegX:
            return "-x";
        case MeshAxis::kPosY:
            return "+y";
        case MeshAxis::kNegY:
            return "-y";
        case MeshAxis::kPosZ:
            return "+z";
        case MeshAxis::kNegZ:
            return "-z";
    }
    return "?";
}

Eigen::Vector3d axis_vector(MeshAxis axis) {
    const int i = static_cast<int>(axis) / 2;
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    v[i] = static_cast<int>(axis) % 2 ? -1.0 : 1.0;
    return v;
}

std::optional<double> parse_length_unit(std::string_view name) {
    if (name == "m") return 1.0;
    if (name == "cm") return 0.01;
    if (name == "mm") return 0.001;
    if (name == "in") return 0.0254;
    if (name == "ft") return 0.3048;
    return std::nullopt;
}

std::optional<Eigen::Matrix3d> placement_rotation(MeshAxis up, MeshAxis forward) {
    const Eigen::Vector3d u = axis_vector(up), f = axis_vector(forward);
    if (std::abs(u.dot(f)) > 0.5) return std::nullopt;
    // Rows: where each new axis comes from (x' = f . p, y' = (u x f) . p, z' = u . p).
    Eigen::Matrix3d R;
    R.row(0) = f.transpose();
    R.row(1) = u.cross(f).transpose();
    R.row(2) = u.transpose();
    return R;
}

TriangleMesh place_mesh(TriangleMesh mesh, const MeshPlacement& p) {
    const auto R = placement_rotation(p.up, p.forward);
    if (!R) {
        throw std::invalid_argument("up axis " + std::string(to_string(p.up)) +
                                    " and forward axis " + std::string(to_string(p.forward)) +
                                    " are parallel");
    }
    if (!(p.scale > 0.0) || !std::isfinite(p.scale))
        throw std::invalid_argument("the scale must be positive");
    const Eigen::Matrix3f M = (p.scale * *R).cast<float>();
    for (Eigen::Vector3f& v : mesh.vertices_m) v = M * v;
    if (p.recentre && !mesh.vertices_m.empty()) {
        Eigen::Vector3f lo = mesh.vertices_m.front(), hi = lo;
        for (const Eigen::Vector3f& v : mesh.vertices_m) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        const Eigen::Vector3f shift(-0.5f * (lo.x() + hi.x()), -0.5f * (lo.y() + hi.y()), -lo.z());
        for (Eigen::Vector3f& v : mesh.vertices_m) v += shift;
    }
    return mesh;
}

std::optional<std::string> implausible_furniture_extent(const TriangleMesh& mesh, ObjectClass cls) {
    if (mesh.vertices_m.empty()) return std::string("the mesh has no vertices");
    Eigen::Vector3f lo = mesh.vertices_m.front(), hi = lo;
    for (const Eigen::Vector3f& v : mesh.vertices_m) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Eigen::Vector3f size = hi - lo;
    const double height = size.z(), footprint = std::max(size.x(), size.y());
    // Real furniture: chairs and stools 0.3-1.6 m tall (a bar stool, a wing chair), tables
    // 0.25-1.2 m (a coffee table, a bar table); nothing is 5 m long, and nothing upright is much
    // lower than it is deep unless it is a low table or a bench.
    const double min_h = cls == ObjectClass::kChair ? 0.3 : 0.25,
                 max_h = cls == ObjectClass::kChair ? 1.6 : 1.2;
    char buf[256];
    if (height < min_h || height > max_h || footprint > 5.0) {
        std::snprintf(buf, sizeof(buf),
                      "%.2f x %.2f x %.2f m is implausible for a %s (%.2f-%.2f m tall expected): "
                      "wrong units or up axis?",
                      size.x(), size.y(), size.z(), std::string(to_string(cls)).c_str(), min_h,
                      max_h);
        return std::string(buf);
    }
    return std::nullopt;
}

}  // namespace makeway
