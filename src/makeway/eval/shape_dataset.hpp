#pragma once
// Training and benchmark data for the shape networks, made by the simulator: generated rooms
// (every style of the wider world unless told otherwise, random dimensions and poses), one LiDAR
// sweep from each of several free viewpoints per room, each object's returns cut out of it the way
// perception sees them (above the ground band, with whatever else stands inside the object's box:
// neighbours' legs, a wall) plus injected depth outliers, in the object's gravity frame with its
// true canonical pose. Shapes carry their SDF and occupancy targets, computed from the mesh.
#include <functional>
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/shape/shape_training.hpp"

namespace makeway::eval {

struct ShapeDatasetParams {
    int scenes = 24;
    std::uint64_t seed = 0;
    int viewpoints_per_scene = 6;             ///< start, waypoint, goal, then random free places
    std::vector<std::string> exclude_styles;  ///< never drawn (training without them)
    std::vector<std::string> only_styles;     ///< every object takes one of these (held-out styles)
    std::size_t min_points = 30;     ///< views with fewer of the object's own returns are dropped
    double max_outlier_share = 0.2;  ///< injected depth outliers: a share in [0, this] per view
    double ground_band_m =
        0.05;  ///< returns this close to the floor are cut (perception's ground removal)
    int sdf_samples = 4000;
    int occupancy_samples = 3000;
    int surface_samples = 2048;  ///< kept per shape for scoring (canonical)
    int threads = 0;             ///< shape targets in parallel (0: all cores)
};

/// Shapes also keep their surface samples and identity for the benchmark.
struct ShapeDataset : shape::ShapeTrainingSet {
    std::vector<std::vector<Eigen::Vector3d>> surface;  ///< per shape, canonical
    std::vector<double> scale_m;                        ///< per shape: the canonical unit [m]
    std::vector<TriangleMesh> mesh_object;              ///< per shape, in its object frame
    std::vector<OrientedBox> box_object;                ///< per shape
    std::vector<int> scene_of_view;                     ///< per view
    std::vector<std::uint32_t> object_of_view;  ///< per view: the object's instance id in its scene
    std::vector<std::size_t> own_points_of_view;  ///< per view: the object's own returns
};

/// Throws std::invalid_argument on unknown style names. `progress(done, total)` per scene.
ShapeDataset generate_shape_dataset(const ShapeDatasetParams& params,
                                    const std::function<void(int, int)>& progress = {});

}  // namespace makeway::eval
