#include "makeway/shape/shape_completion.hpp"

#include <stdexcept>

namespace makeway::shape {

TsdfVolume fuse_views(const ShapeModel& model,
                      const std::vector<std::vector<Eigen::Vector3d>>& views,
                      const std::vector<Eigen::Vector3d>& origins) {
    if (views.size() != origins.size())
        throw std::invalid_argument("one sensor origin per view is needed");
    TsdfVolume tsdf(model.params().grid, model.params().truncation_cells);
    for (std::size_t v = 0; v < views.size(); ++v) tsdf.integrate(views[v], origins[v]);
    return tsdf;
}

TriangleMesh grid_isosurface(const CubeGrid& grid, const std::vector<float>& values, double level,
                             bool inside_below) {
    const Eigen::Vector3i dims = Eigen::Vector3i::Constant(grid.resolution);
    return extract_isosurface(values, dims, grid.centre(0, 0, 0), grid.cell(), level, inside_below);
}

Completion complete_shape(const ShapeModel& model, ObjectClass cls,
                          const std::vector<std::vector<Eigen::Vector3d>>& views,
                          const std::vector<Eigen::Vector3d>& origins,
                          const CompletionParams& params) {
    if (shape_class_index(cls) < 0) throw std::invalid_argument("no shape networks for this class");
    Completion out;
    const TsdfVolume tsdf = fuse_views(model, views, origins);
    out.observed_cells = tsdf.observed_cells();
    std::size_t total = 0;
    for (const auto& v : views) total += v.size();
    const std::size_t every =
        std::max<std::size_t>(1, total / static_cast<std::size_t>(std::max(1, params.fit_points)));
    std::vector<Eigen::Vector3d> surface, free;
    std::size_t k = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
        for (const auto& p : views[v]) {
            if (k++ % every) continue;
            surface.push_back(p);
            const Eigen::Vector3d d = p - origins[v];
            if (d.norm() > params.free_offset * 1.5)
                free.push_back(p - params.free_offset * d.normalized());
        }
    }
    out.code = model.fit_latent(cls, surface, free, params.fit_iterations);
    out.grid = model.params().grid;
    if (params.mesh_resolution > 0) out.grid.resolution = params.mesh_resolution;
    const std::vector<Eigen::Vector3d> centres = out.grid.centres();
    if (params.prior_field) {
        out.prior_sdf = model.sdf(cls, out.code, centres);
        out.prior_mesh = grid_isosurface(out.grid, out.prior_sdf, 0.0, true);
    }
    out.occupancy = model.occupancy(cls, tsdf, out.code, centres);
    out.mesh = grid_isosurface(out.grid, out.occupancy, 0.5, false);
    return out;
}

}  // namespace makeway::shape
