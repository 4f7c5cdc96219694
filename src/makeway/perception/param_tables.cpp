#include "makeway/perception/param_tables.hpp"

namespace makeway::perception {

const ParamTable<GroundPlaneParams>& ground_plane_table() {
    using G = GroundPlaneParams;
    static const ParamTable<G> table = [] {
        ParamTable<G> t;
        t.add("inlier_distance_m", &G::inlier_distance_m, open(0.0, 1.0), "")
            .add("iterations", &G::iterations, closed(1, 100000), "")
            .add("max_tilt_deg", &G::max_tilt_deg, above(0.0, 90.0),
                 "the ground is roughly below a robot's sensor")
            .add("voxel_m", &G::voxel_m, below(0.0, 1.0),
                 "RANSAC hypotheses scored by inlier area (voxels of this size; 0: points)")
            .add("min_sensor_height_m", &G::min_sensor_height_m, closed(0.0, 10.0), "")
            .add("seed", &G::seed, closed(0.0, 1.8446744073709552e19), "");
        return t;
    }();
    return table;
}

const ParamTable<GroundFilterParams>& ground_filter_table() {
    using F = GroundFilterParams;
    static const ParamTable<F> table = [] {
        ParamTable<F> t;
        t.add("ground_band_m", &F::ground_band_m, closed(0.0, 10.0),
              "points lower than this above the ground are removed")
            .add("ceiling_height_m", &F::ceiling_height_m, above(0.0, 100.0),
                 "points higher than this above the ground are removed")
            .require([](const F& f) { return f.ground_band_m < f.ceiling_height_m; },
                     "need 0 <= ground_band_m < ceiling_height_m");
        return t;
    }();
    return table;
}

}  // namespace makeway::perception
