#include "makeway/eval/object_source.hpp"

namespace makeway::eval {

std::vector<ObjectEstimate> ground_truth_objects(const sim::Scene& scene,
                                                 const std::vector<sim::ObjectModel>& models,
                                                 double t_s) {
    return sim::object_estimates_at(scene, models, t_s);
}

std::vector<ObjectEstimate> GroundTruthObjects::objects(const ObjectSourceInput& input) {
    return ground_truth_objects(scene_, models_, input.t_s);
}

}  // namespace makeway::eval
