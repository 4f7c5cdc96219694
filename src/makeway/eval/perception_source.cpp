#include "makeway/eval/perception_source.hpp"

#include "makeway/sim/furniture.hpp"

namespace makeway::eval {

verification::CadLibrary default_cad_library() {
    verification::CadLibrary lib;
    for (ObjectClass cls : kAllObjectClasses) {
        for (sim::FurnitureStyle s : sim::styles_of(cls)) lib.add(std::string(sim::to_string(s)), cls, sim::make_furniture(s, 0).mesh_object);
    }
    return lib;
}

PerceptionObjects::PerceptionObjects(const perception::Detector& detector, const verification::CadLibrary* library,
                                     const PerceptionSourceParams& params)
    : detector_(detector), library_(library), params_(params), map_(params.tracker) {}

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
        std::vector<Detection> verified;
        for (const Detection& d : dets) {
            std::optional<double> floor_z;
            if (ground_->found) floor_z = ground_->floor_z_at(d.box_sensor.centre_m.x(), d.box_sensor.centre_m.y());
            const verification::VerifiedDetection v = verification::verify_detection(cloud, d, *library_, {}, floor_z);
            if (!v.accepted) continue;
            Detection r = d;
            r.box_sensor = v.box_sensor;
            r.score = v.p_exist;  // eq. (2): the existence evidence the map fuses
            verified.push_back(r);
        }
        dets = std::move(verified);
    }
    ++keyframes_;
    last_ = map_.update(dets, T_world_keyframe, in.t_s).objects_world;
    return last_;
}

}  // namespace makeway::eval
