#pragma once
// One object's shape from its observations, in its canonical frame: F_0's code fitted to the
// returns (surface) and to points in front of them (free space), the TSDF fused from every
// observation, F_1's occupancy on the model's grid and its 0.5 isosurface (marching tetrahedra).
#include <vector>

#include "makeway/shape/shape_model.hpp"

namespace makeway::shape {

struct CompletionParams {
    int fit_iterations = 60;  ///< F_0's code fit (0: F_0's mean code, no fit)
    int fit_points = 256;     ///< surface points the fit uses (every k-th)
    double free_offset =
        0.15;  ///< free-space points this far in front of each return (canonical units)
    bool prior_field =
        true;  ///< also F_0's SDF on the grid and its mesh (the prior alone, for comparison)
    int mesh_resolution =
        0;  ///< cells per side of the grid F_1 is queried on (0: the model's TSDF grid)
};

struct Completion {
    Latent code{};
    CubeGrid grid;                  ///< where the fields below are sampled (cell centres)
    std::vector<float> prior_sdf;   ///< F_0 (empty without prior_field)
    std::vector<float> occupancy;   ///< F_1
    TriangleMesh prior_mesh, mesh;  ///< canonical
    std::size_t observed_cells = 0;
};

/// `views` and `origins` in the canonical frame, one origin per view. Throws std::invalid_argument
/// for a class without networks or mismatched sizes.
Completion complete_shape(const ShapeModel& model, ObjectClass cls,
                          const std::vector<std::vector<Eigen::Vector3d>>& views,
                          const std::vector<Eigen::Vector3d>& origins,
                          const CompletionParams& params = {});

/// The TSDF of the views (the model's grid and truncation).
TsdfVolume fuse_views(const ShapeModel& model,
                      const std::vector<std::vector<Eigen::Vector3d>>& views,
                      const std::vector<Eigen::Vector3d>& origins);

/// Mesh of a field on a CubeGrid's cell centres (inside below `level` when inside_below).
TriangleMesh grid_isosurface(const CubeGrid& grid, const std::vector<float>& values, double level,
                             bool inside_below);

}  // namespace makeway::shape
