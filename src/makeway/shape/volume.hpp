#pragma once
// Volumes over an object's canonical cube [-half_extent, half_extent]^3 (the frame F_n solves
// for: the object's box centre at the origin, its half diagonal 1): the TSDF and weight volumes
// that F_1 reads, and the isosurface extraction that turns a field sampled on such a grid into a
// mesh.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "makeway/common/triangle_mesh.hpp"

namespace makeway::shape {

/// A cubic grid of `resolution`^3 cell centres over [-half_extent, half_extent]^3, x fastest.
struct CubeGrid {
    int resolution = 32;
    double half_extent = 1.1;
    double cell() const { return 2.0 * half_extent / resolution; }
    Eigen::Vector3d centre(int x, int y, int z) const {
        return Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5) * cell() -
               Eigen::Vector3d::Constant(half_extent);
    }
    std::size_t index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * static_cast<std::size_t>(resolution) +
                static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(resolution) +
               static_cast<std::size_t>(x);
    }
    std::size_t size() const {
        return static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution) *
               static_cast<std::size_t>(resolution);
    }
    /// Every cell centre, in index order.
    std::vector<Eigen::Vector3d> centres() const;
};

/// Truncated signed distance fusion of range measurements (Curless and Levoy), for a scanning
/// LiDAR: each return's ray is walked from where it enters the cube to `truncation` behind the
/// return; cells in front of the return by more than the truncation read "free" (+1), cells
/// within it read (range - depth) / truncation, cells behind are not touched (unseen). Values are
/// running weighted means; the weight volume counts the rays that touched a cell (F_1's
/// confidence input: 0 where nothing was seen).
class TsdfVolume {
  public:
    explicit TsdfVolume(const CubeGrid& grid = {}, double truncation_cells = 2.5);
    /// Returns and the sensor origin in the canonical frame (non-finite points are skipped).
    void integrate(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin);
    const CubeGrid& grid() const { return grid_; }
    const std::vector<float>& tsdf() const { return tsdf_; }
    const std::vector<float>& weight() const { return weight_; }
    std::size_t observed_cells() const;

  private:
    CubeGrid grid_;
    double truncation_;
    std::vector<float> tsdf_, weight_;
};

/// The isosurface `value == level` of a field sampled at the nodes of a regular grid (`dims`
/// nodes, x fastest, node (i, j, k) at origin + spacing * (i, j, k)), by marching tetrahedra: each
/// cube cut into six tetrahedra around its main diagonal (the same cut in every cube, so
/// neighbouring faces agree and the surface has no cracks), vertices on grid edges shared between
/// cells. Triangles face the side where value > level when `inside_below` (an SDF), the side where
/// value < level otherwise (an occupancy). Non-finite values count as outside.
TriangleMesh extract_isosurface(const std::vector<float>& values, const Eigen::Vector3i& dims,
                                const Eigen::Vector3d& origin, double spacing, double level,
                                bool inside_below);

/// Bidirectional Chamfer-L1: the mean of the two directions' mean nearest-neighbour distances.
/// Infinity when either set is empty.
double chamfer_l1(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// |A and B| / |A or B| of two occupancy masks of one size; 1 when both are empty.
double volumetric_iou(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

}  // namespace makeway::shape
