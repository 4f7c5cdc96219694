#include "makeway/common/triangle_mesh.hpp"

#include <string>

namespace makeway {

std::string TriangleMesh::validity_error() const {
    for (std::size_t i = 0; i < vertices_m.size(); ++i) {
        if (!vertices_m[i].allFinite()) return "vertex " + std::to_string(i) + " is not finite";
    }
    const auto n = static_cast<int>(vertices_m.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const auto& tri = triangles[t];
        if ((tri.array() < 0).any() || (tri.array() >= n).any()) {
            return "triangle " + std::to_string(t) + " indexes a missing vertex";
        }
    }
    return {};
}

void TriangleMesh::append(const TriangleMesh& other) {
    const int offset = static_cast<int>(vertices_m.size());
    vertices_m.insert(vertices_m.end(), other.vertices_m.begin(), other.vertices_m.end());
    for (const auto& tri : other.triangles)
        triangles.push_back(tri + Eigen::Vector3i::Constant(offset));
}

void mesh_bounds(const TriangleMesh& mesh, Eigen::Vector3d& min_m, Eigen::Vector3d& max_m) {
    min_m = max_m = Eigen::Vector3d::Zero();
    if (mesh.vertices_m.empty()) return;
    min_m = max_m = mesh.vertices_m.front().cast<double>();
    for (const auto& v : mesh.vertices_m) {
        min_m = min_m.cwiseMin(v.cast<double>());
        max_m = max_m.cwiseMax(v.cast<double>());
    }
}

}  // namespace makeway
