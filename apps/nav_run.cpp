#include "apps/nav_run.hpp"

#include <optional>
#include <stdexcept>

#include "makeway/eval/scene_cad.hpp"

namespace makeway::apps {

eval::NavRunResult run_nav_method(const sim::Scene& scene, const std::string& name,
                                  const eval::NavParams& params,
                                  const perception::Detector* detector,
                                  const verification::ShapePrior* shapes) {
    const std::optional<eval::NavMethod> method = eval::nav_method(name, params.robot);
    if (!method) throw std::invalid_argument("unknown navigation method '" + name + "'");
    if (method->online) {
        if (!detector) throw std::invalid_argument("the full system 'ours' needs detector weights");
        if (shapes)
            return eval::run_navigation_online(scene, *method, *detector, nullptr, params, shapes);
        // The room's furniture models, as in the paper: a deployment's CAD files.
        const verification::CadLibrary cad = eval::scene_cad_library(scene);
        return eval::run_navigation_online(scene, *method, *detector, &cad, params);
    }
    if (!method->affordance) {
        eval::NoObjects none;
        return eval::run_navigation(scene, *method, none, params);
    }
    // The truth, with the parts of each object the body can hit (as ours has them from its CAD
    // fits).
    eval::GroundTruthObjects truth(scene, sim::models_of(scene),
                                   params.system.navigator.monitor.body);
    return eval::run_navigation(scene, *method, truth, params);
}

void plan_with_zones(eval::NavParams& params,
                     const std::shared_ptr<const costmap::LearnedZones>& zones) {
    if (!zones) return;
    params.risk_zones = params.system.navigator.affordance;
    params.system.navigator.affordance.learned = zones;
}

}  // namespace makeway::apps
