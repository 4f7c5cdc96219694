#include "makeway/pipeline/mapping_system.hpp"

#include <chrono>

namespace makeway::pipeline {

Costmap free_area(const Pose2& centre, double side_m, double resolution_m) {
    const int cells = static_cast<int>(side_m / resolution_m);
    return Costmap(Eigen::Vector2d(centre.x_m, centre.y_m) - Eigen::Vector2d::Constant(0.5 * side_m), resolution_m, cells, cells);
}

MappingSystem::MappingSystem(const SystemParams& params, const Pose2& start_pose, const Costmap& static_map,
                             bool restrict_objects, const perception::ObjectDetector* detector,
                             const verification::CadLibrary* library)
    : static_map_(static_map), pipeline_(params, start_pose, detector, library), costmap_(static_map, params.navigator) {
    if (restrict_objects) {
        // Within the map's known area. Not "in its free space" as with a map of walls alone: a
        // SLAM map of a furnished room holds the furniture as occupied cells.
        pipeline_.set_object_region([this](const Eigen::Vector2d& p) {
            const auto c = static_map_.cost_at(p);
            return c.has_value() && *c != cost::kUnknown;
        });
    }
}

MappingStep MappingSystem::process(const Sweep& sweep) {
    MappingStep out;
    out.sweep = pipeline_.process_sweep(sweep);
    objects_ = out.sweep.objects;
    const auto t0 = std::chrono::steady_clock::now();
    costmap_.update(&out.sweep.points_world, out.sweep.T_world_sensor_end.translation(), objects_);
    out.costmap_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace makeway::pipeline
