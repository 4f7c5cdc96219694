#pragma once
// Indexed triangle mesh: CAD models, scene geometry.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace makeway {

struct TriangleMesh {
    std::vector<Eigen::Vector3f> vertices_m;
    std::vector<Eigen::Vector3i>
        triangles;  ///< vertex indices, counter-clockwise seen from outside

    std::size_t num_triangles() const { return triangles.size(); }
    /// Empty string when every index is in range and every vertex finite, else what is wrong.
    std::string validity_error() const;
    /// Appends another mesh (indices shifted).
    void append(const TriangleMesh& other);
};

/// Axis-aligned bounds of the vertices [m]; zero when empty.
void mesh_bounds(const TriangleMesh& mesh, Eigen::Vector3d& min_m, Eigen::Vector3d& max_m);

}  // namespace makeway
