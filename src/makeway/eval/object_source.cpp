#include "makeway/eval/object_source.hpp"

namespace makeway::eval {

std::vector<ObjectEstimate> ground_truth_objects(const sim::Scene& scene, const std::vector<sim::ObjectModel>& models,
                                                 double t_s) {
    std::vector<ObjectEstimate> out;
    for (const sim::ObjectState& s : sim::object_states_at(scene, models, t_s)) {
        ObjectEstimate o;
        o.id = s.id;
        o.cls = s.cls;
        o.box_world = s.box_world;
        o.velocity_mps = s.velocity_mps;
        out.push_back(o);
    }
    return out;
}

std::vector<ObjectEstimate> GroundTruthObjects::objects(const ObjectSourceInput& input) {
    return ground_truth_objects(scene_, models_, input.t_s);
}

}  // namespace makeway::eval
