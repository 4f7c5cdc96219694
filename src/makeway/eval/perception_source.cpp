#include "makeway/eval/perception_source.hpp"

#include <algorithm>
#include <set>

#include "makeway/sim/furniture.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::eval {

verification::CadLibrary default_cad_library() {
    verification::CadLibrary lib;
    for (ObjectClass cls : kAllObjectClasses) {
        for (sim::FurnitureStyle s : sim::styles_of(cls)) lib.add(std::string(sim::to_string(s)), cls, sim::make_furniture(s, 0).mesh_object);
    }
    return lib;
}

verification::CadLibrary scene_cad_library(const sim::Scene& scene) {
    verification::CadLibrary lib;
    std::set<std::string> added;
    for (const sim::SceneObject& o : scene.objects) {
        const std::string name = o.style.empty() ? o.mesh_file + "@" + std::to_string(o.scale) : o.style + "_" + std::to_string(o.model_seed);
        if (added.insert(name).second) lib.add(name, o.cls, sim::model_of(o).mesh_object);
    }
    return lib;
}

tracking::TrackerParams tracker_params_for(const perception::Detector& detector, tracking::TrackerParams params) {
    // Misses count only where the detector can see: inside the circle its square grid contains,
    // less half a large chair so that the whole object is inside.
    params.miss_range_m = std::min(params.sensor_range_m, detector.params().grid.range_m - 0.5);
    return params;
}

PerceptionObjects::PerceptionObjects(const perception::Detector& detector, const verification::CadLibrary* library,
                                     const PerceptionSourceParams& params)
    : detector_(detector), library_(library), params_(params), map_(tracker_params_for(detector, params.tracker)) {}

std::vector<ObjectEstimate> PerceptionObjects::objects(const ObjectSourceInput& in) {
    if (!in.points_sensor) return last_;
    perception::StampedSweep sweep;
    sweep.points_sensor = *in.points_sensor;
    sweep.stamp_s = in.t_s;
    sweep.T_world_sensor_start = sweep.T_world_sensor_end = in.T_world_sensor;
    accumulator_.add(std::move(sweep));
    if (!accumulator_.full() || sweeps_++ % static_cast<std::size_t>(params_.keyframe_every) != 0) return last_;
    // Keyframe: accumulate, remove ground (plane from start-up) and ceiling.
    Isometry3 T_world_keyframe;
    const PointCloud raw = accumulator_.keyframe(&T_world_keyframe);
    if (!ground_ || !ground_->found) ground_ = perception::fit_ground_plane(raw, {});
    const PointCloud cloud = ground_->found ? perception::remove_ground_and_ceiling(raw, *ground_, {}) : raw;
    // Detect, verify, track.
    std::vector<Detection> dets = detector_.detect(cloud);
    if (params_.verification && library_) {
        const perception::GroundPlaneResult& ground = *ground_;
        dets = verification::accepted_detections(verification::verify_detections(cloud, dets, *library_, {}, [&](double x, double y) -> std::optional<double> {
            if (!ground.found) return std::nullopt;
            return ground.floor_z_at(x, y);
        }));
    }
    ++keyframes_;
    last_ = map_.update(dets, T_world_keyframe, in.t_s).objects_world;
    return last_;
}

}  // namespace makeway::eval
