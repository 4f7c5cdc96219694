#pragma once
// A simulated scan of one chair and a CAD library of its model, for the verification tests.
#include <cstdint>
#include <string>
#include <vector>

#include "../sim/sim_test_util.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/icp.hpp"

namespace makeway::verification {

// A room with one chair; the sensor 0.45 m above the floor, 2.5 m away. Returns the scan (sensor
// frame, floor and ceiling dropped by height) and the chair's true pose in the sensor frame.
struct ChairScan {
    PointCloud cloud_sensor;
    Pose4 truth;
    OrientedBox box_sensor;
};

inline ChairScan scan_chair(sim::FurnitureStyle style, std::uint64_t model_seed, double yaw,
                            std::uint64_t seed) {
    sim::Scene s = sim::testing_util::box_room(5.0);
    sim::SceneObject chair;
    chair.id = 3;
    chair.cls = sim::class_of(style);
    chair.style = std::string(sim::to_string(style));
    chair.model_seed = model_seed;
    chair.pose = {1.0, 0.6, yaw};
    s.objects.push_back(chair);
    const sim::ObjectModel model = sim::model_of(chair);
    sim::World world(s, {model});
    const Isometry3 T_world_sensor = make_T_xyz_yaw({-1.5, 0.0, 0.45}, 0.0);
    ChairScan out;
    sim::LidarParams lidar;  // the real VLP-32C pattern, noise and dropout
    PointCloud raw;
    for (int k = 0; k < 5; ++k)
        raw.append(sim::simulate_sweep(
            world, lidar, [&](double) { return T_world_sensor; }, 0.1 * k, seed, k));
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const double h = raw.xyz[i].z() + 0.45;
        if (h > 0.08 && h < 2.2) keep.push_back(i);
    }
    out.cloud_sensor = raw.select(keep);
    const Isometry3 T_sensor_object = T_world_sensor.inverse() * lift_to_3d(chair.pose);
    out.truth.t_m = T_sensor_object.translation();
    out.truth.yaw_rad = yaw_of(T_sensor_object);
    out.box_sensor = model.box_object.transformed(T_sensor_object);
    return out;
}

inline CadLibrary library_with(sim::FurnitureStyle style, std::uint64_t model_seed,
                               const CadLibraryParams& params = {}) {
    CadLibrary lib(params);
    lib.add(std::string(sim::to_string(style)), sim::class_of(style),
            sim::make_furniture(style, model_seed).mesh_object);
    return lib;
}

}  // namespace makeway::verification
