#include "makeway/odometry/param_tables.hpp"

namespace makeway::odometry {

const ParamTable<OdometryParams>& odometry_table() {
    using O = OdometryParams;
    static const ParamTable<O> table = [] {
        ParamTable<O> t;
        t.add_ref(
             "voxel_m", [](O& o) -> double& { return o.map.voxel_m; }, above(0.01, 10.0),
             "map voxels; each keeps at most max_points_per_voxel points and its shape")
            .add_ref(
                "max_points_per_voxel", [](O& o) -> int& { return o.map.max_points_per_voxel; },
                closed(1, 1000), "")
            .add_ref(
                "planarity", [](O& o) -> double& { return o.map.planarity; }, open(0.0, 1.0),
                "spread ratio below which a voxel is a plane (or, of the larger two, a line)")
            .add("source_voxel_m", &O::source_voxel_m, above(0.0, 10.0),
                 "registration uses one point per voxel of this size")
            .add("insert_voxel_m", &O::insert_voxel_m, above(0.0, 10.0),
                 "the map receives one point per voxel of this size")
            .add("min_range_m", &O::min_range_m, closed(0.0, 1000.0),
                 "closer returns (the robot, a person at the sensor) unused")
            .add("max_range_m", &O::max_range_m, above(0.0, 1000.0), "")
            .add("min_height_m", &O::min_height_m, closed(-5.0, 5.0),
                 "points lower above the base (the floor) are left out")
            .add("map_radius_m", &O::map_radius_m, above(0.0, 1000.0),
                 "voxels farther from the robot are dropped")
            .add("max_iterations", &O::max_iterations, closed(1, 1000), "")
            .add("convergence_m", &O::convergence_m, above(0.0, 1.0),
                 "iterations stop when a step moves less (rotation at 1 m counted alike)")
            .add("initial_threshold_m", &O::initial_threshold_m, above(0.0, 100.0),
                 "correspondence distance until the adaptive one has 5 sweeps of history")
            .add("min_threshold_m", &O::min_threshold_m, above(0.0, 100.0), "")
            .add("max_threshold_m", &O::max_threshold_m, above(0.0, 100.0), "")
            .add("residual_sigma_m", &O::residual_sigma_m, above(0.0, 10.0),
                 "one correspondence's noise, weighed against the wheel prior")
            .add("wheel_sigma_m", &O::wheel_sigma_m, above(0.0, 10.0),
                 "the wheel prediction's sigma per sweep: floor ...")
            .add("wheel_sigma_per_m", &O::wheel_sigma_per_m, closed(0.0, 10.0),
                 "... plus this share of the distance driven")
            .add("wheel_sigma_rad", &O::wheel_sigma_rad, above(0.0, 10.0), "")
            .add("wheel_sigma_per_rad", &O::wheel_sigma_per_rad, closed(0.0, 10.0), "")
            .add("deskew", &O::deskew, "move each point with the pose at its own time")
            .add("threads", &O::threads, closed(1, 256),
                 "threads of the correspondence search (the same poses for any count)")
            .require([](const O& o) { return o.min_range_m < o.max_range_m; },
                     "needs 0 <= min_range_m < max_range_m")
            .require(
                [](const O& o) {
                    return o.min_threshold_m <= o.initial_threshold_m &&
                           o.initial_threshold_m <= o.max_threshold_m;
                },
                "needs 0 < min_threshold_m <= initial_threshold_m <= max_threshold_m");
        return t;
    }();
    return table;
}

}  // namespace makeway::odometry
