#include "makeway/eval/object_source.hpp"

#include "makeway/sim/robot.hpp"
#include "makeway/verification/part_outlines.hpp"

namespace makeway::eval {

GroundTruthObjects::GroundTruthObjects(const sim::Scene& scene,
                                       std::vector<sim::ObjectModel> models,
                                       const std::optional<BodyHeights>& parts_band)
    : scene_(scene), models_(std::move(models)) {
    if (!parts_band) return;
    // The mesh's surface in the band, every 2 cm (the simulator's contact points), at a height
    // inside the band: part_outlines needs only which points are in it.
    for (const sim::ObjectModel& m : models_) {
        std::vector<Eigen::Vector3d> band;
        for (const Eigen::Vector2d& q : sim::low_surface_points(m.mesh_object, *parts_band, 0.02))
            band.emplace_back(q.x(), q.y(), parts_band->ground_clearance_m);
        parts_object_.push_back(verification::part_outlines(band, *parts_band));
    }
}

std::vector<ObjectEstimate> ground_truth_objects(const sim::Scene& scene,
                                                 const std::vector<sim::ObjectModel>& models,
                                                 double t_s) {
    return sim::object_estimates_at(scene, models, t_s);
}

std::vector<ObjectEstimate> GroundTruthObjects::objects(const ObjectSourceInput& input) {
    // The states once: their poses place the parts, and they are the estimates.
    const std::vector<sim::ObjectState> states = sim::object_states_at(scene_, models_, input.t_s);
    std::vector<ObjectEstimate> out = sim::object_estimates(states);
    for (std::size_t i = 0; i < out.size() && i < parts_object_.size(); ++i) {
        for (const Polygon2& part : parts_object_[i]) {
            Polygon2 world;
            world.reserve(part.size());
            for (const Eigen::Vector2d& q : part)
                world.push_back(
                    (states[i].T_world_object * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>());
            out[i].parts_world.push_back(std::move(world));
        }
    }
    return out;
}

}  // namespace makeway::eval
