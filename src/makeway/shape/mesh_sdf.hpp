#pragma once
// Signed distance to a triangle mesh, for the shape networks' training targets and for scoring
// completions. The distance is exact (closest point on each triangle, Ericson's region test) and
// searched through a bounding-volume hierarchy (median splits, nearest child first, pruned by box
// distance). Inside is decided by the generalised winding number (the solid angles of all
// triangles summed, Van Oosterom and Strackee): furniture is a union of closed, overlapping parts,
// where ray parity fails but the winding number is >= 1 inside any part and 0 outside. It costs
// one pass over the triangles per query, which training data and scoring can afford.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "makeway/common/triangle_mesh.hpp"

namespace makeway::shape {

/// The point of triangle (a, b, c) nearest p.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

class MeshSdf {
  public:
    /// The mesh's vertices scaled by `scale` after `offset` is subtracted: v' = (v - offset) *
    /// scale (the canonical frame of the shape networks). Throws std::invalid_argument on an empty
    /// or invalid mesh.
    explicit MeshSdf(const TriangleMesh& mesh,
                     const Eigen::Vector3d& offset = Eigen::Vector3d::Zero(), double scale = 1.0);

    double unsigned_distance(const Eigen::Vector3d& q) const;
    double winding_number(const Eigen::Vector3d& q) const;
    bool inside(const Eigen::Vector3d& q) const { return winding_number(q) > 0.5; }
    double signed_distance(const Eigen::Vector3d& q) const {
        return inside(q) ? -unsigned_distance(q) : unsigned_distance(q);
    }

    /// Points on the surface, area-weighted, seeded.
    std::vector<Eigen::Vector3d> sample_surface(std::size_t count, std::uint64_t seed) const;
    const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
    const std::vector<Eigen::Vector3i>& triangles() const { return triangles_; }

  private:
    struct Node {
        Eigen::AlignedBox3d box;
        int left = -1, right = -1;  ///< children, or -1 for a leaf
        int first = 0, count = 0;   ///< a leaf's range in order_
    };
    int build(int first, int count);
    double box_distance2(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& q) const;

    std::vector<Eigen::Vector3d> vertices_;
    std::vector<Eigen::Vector3i> triangles_;
    std::vector<int> order_;
    std::vector<Node> nodes_;
    std::vector<double> cumulative_area_;
};

}  // namespace makeway::shape
