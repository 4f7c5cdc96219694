#include "makeway/sim/scene_dynamics.hpp"

#include <cmath>
#include <stdexcept>

#include "makeway/common/angles.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::sim {

ObjectModel model_of(const SceneObject& object) {
    ObjectModel model;
    if (object.user_mesh) {
        model.mesh_object = *object.user_mesh;
        Eigen::Vector3d lo, hi;
        mesh_bounds(model.mesh_object, lo, hi);
        model.box_object.centre_m = 0.5 * (lo + hi);
        model.box_object.size_m = hi - lo;
        return model;
    }
    const auto style = parse_furniture_style(object.style);
    if (!style) throw std::invalid_argument("unknown furniture style '" + object.style + "'");
    FurnitureModel f = make_furniture(*style, object.model_seed);
    model.mesh_object = std::move(f.mesh_object);
    model.box_object = f.box_object;
    return model;
}

std::vector<ObjectModel> models_of(const Scene& scene) {
    std::vector<ObjectModel> models;
    models.reserve(scene.objects.size());
    for (const SceneObject& o : scene.objects) models.push_back(model_of(o));
    return models;
}

Pose2 object_pose_at(const Scene& scene, std::size_t index, double t_s,
                     Eigen::Vector2d* velocity_mps) {
    const SceneObject& o = scene.objects[index];
    Pose2 pose = o.pose;
    if (velocity_mps) velocity_mps->setZero();
    for (const ChairPusher& p : scene.pushers) {
        if (p.chair_id != o.id || p.period_s <= 0.0) continue;
        const double w = 2.0 * kPi / p.period_s;
        const double phase = w * (t_s + p.phase_s);
        const double offset = -p.pull_m * 0.5 * (1.0 - std::cos(phase));  // along -x: pulled out
        const double speed = -p.pull_m * 0.5 * w * std::sin(phase);
        const Eigen::Vector2d forward(std::cos(o.pose.yaw_rad), std::sin(o.pose.yaw_rad));
        pose.x_m += offset * forward.x();
        pose.y_m += offset * forward.y();
        if (velocity_mps) *velocity_mps = speed * forward;
    }
    return pose;
}

std::vector<ObjectState> object_states_at(const Scene& scene,
                                          const std::vector<ObjectModel>& models, double t_s) {
    std::vector<ObjectState> out;
    out.reserve(scene.objects.size());
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        ObjectState s;
        s.id = scene.objects[i].id;
        s.cls = scene.objects[i].cls;
        s.T_world_object = lift_to_3d(object_pose_at(scene, i, t_s, &s.velocity_mps));
        s.box_world = models[i].box_object.transformed(s.T_world_object);
        out.push_back(s);
    }
    return out;
}

Eigen::Vector2d walker_position_at(const Walker& walker, double t_s, double* heading_rad) {
    const auto& r = walker.route_m;
    if (r.empty()) return Eigen::Vector2d::Zero();
    double length = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) length += (r[(i + 1) % r.size()] - r[i]).norm();
    if (length <= 0.0 || r.size() < 2) return r.front();
    double s = std::fmod(walker.speed_mps * (t_s + walker.phase_s), length);
    if (s < 0.0) s += length;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const Eigen::Vector2d a = r[i], b = r[(i + 1) % r.size()];
        const double seg = (b - a).norm();
        if (s <= seg && seg > 0.0) {
            if (heading_rad) *heading_rad = std::atan2(b.y() - a.y(), b.x() - a.x());
            return a + (s / seg) * (b - a);
        }
        s -= seg;
    }
    return r.front();
}

TriangleMesh make_person_mesh() {
    TriangleMesh m;
    add_cylinder(m, Eigen::Vector3d(0, 0, 0), kPersonRadius_m * 0.8, 1.45, 12);
    add_sphere(m, Eigen::Vector3d(0, 0, 1.6), 0.12, 12);
    return m;
}

std::vector<ObjectEstimate> object_estimates(const std::vector<ObjectState>& states) {
    std::vector<ObjectEstimate> out;
    out.reserve(states.size());
    for (const ObjectState& s : states) {
        ObjectEstimate o;
        o.id = s.id;
        o.cls = s.cls;
        o.box_world = s.box_world;
        o.velocity_mps = s.velocity_mps;
        out.push_back(o);
    }
    return out;
}

std::vector<ObjectEstimate> object_estimates_at(const Scene& scene,
                                                const std::vector<ObjectModel>& models,
                                                double t_s) {
    return object_estimates(object_states_at(scene, models, t_s));
}

}  // namespace makeway::sim
