#include "makeway/sim/scene.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace makeway::sim {

std::vector<std::string> Scene::validate() const {
    std::vector<std::string> p;
    if (!(floor_max_m.array() > floor_min_m.array()).all())
        p.push_back("floor: max must exceed min");
    // Bounds that fail fast instead of stalling: a building floor, not a city (the costmap has a
    // cell per 5 cm), and counts of things a room holds.
    if (!((floor_max_m - floor_min_m).maxCoeff() <= kMaxFloorExtent_m))
        p.push_back("floor: at most 200 m on a side");
    if (walls.size() > kMaxStructures || pillars.size() > kMaxStructures)
        p.push_back("at most 10000 walls and 10000 pillars");
    if (objects.size() > kMaxObjects) p.push_back("at most 2000 objects");
    if (walkers.size() > kMaxWalkers || pushers.size() > kMaxObjects)
        p.push_back("at most 200 walkers and 2000 pushers");
    if (!(ceiling_height_m > 0.5 && ceiling_height_m < 20.0))
        p.push_back("ceiling_height_m must be in (0.5, 20)");
    std::set<std::uint32_t> ids;
    for (const SceneObject& o : objects) {
        const std::string what = "object " + std::to_string(o.id);
        if (o.id == 0) p.push_back("object ids must be > 0");
        if (!ids.insert(o.id).second) p.push_back(what + ": duplicate id");
        if (o.style.empty() == o.mesh_file.empty())
            p.push_back(what + ": give exactly one of style and mesh");
        if (!(o.scale > 0.0 && o.scale < 100.0)) p.push_back(what + ": scale must be in (0, 100)");
        if (!std::isfinite(o.pose.x_m) || !std::isfinite(o.pose.y_m) ||
            !std::isfinite(o.pose.yaw_rad)) {
            p.push_back(what + ": pose must be finite");
        }
    }
    for (const SceneObject& o : objects) {
        if (o.table_id != 0 && !ids.count(o.table_id)) {
            p.push_back("object " + std::to_string(o.id) + ": table " + std::to_string(o.table_id) +
                        " does not exist");
        }
    }
    for (const ChairPusher& push : pushers) {
        if (!ids.count(push.chair_id))
            p.push_back("pusher: chair " + std::to_string(push.chair_id) + " does not exist");
        if (!(push.period_s > 0.0)) p.push_back("pusher: period_s must be > 0");
        if (!(push.pull_m >= 0.0 && push.pull_m < 3.0))
            p.push_back("pusher: pull_m must be in [0, 3)");
    }
    for (const Walker& w : walkers) {
        if (w.route_m.size() < 2) p.push_back("walker: route needs at least 2 points");
        if (!(w.speed_mps >= 0.0 && w.speed_mps < 5.0))
            p.push_back("walker: speed_mps must be in [0, 5)");
    }
    const auto near_floor = [&](const Eigen::Vector2d& q) {
        return (q.array() >= floor_min_m.array() - kMaxBeyondFloor_m).all() &&
               (q.array() <= floor_max_m.array() + kMaxBeyondFloor_m).all();
    };
    const std::string beyond = " lies more than " +
                               std::to_string(static_cast<int>(kMaxBeyondFloor_m)) +
                               " m beyond the floor";
    for (const Wall& w : walls) {
        if (!near_floor(w.a_m) || !near_floor(w.b_m)) p.push_back("wall: an end" + beyond);
    }
    for (const Pillar& q : pillars) {
        if (!near_floor(q.centre_m)) p.push_back("pillar: its centre" + beyond);
    }
    for (const SceneObject& o : objects) {
        if (std::isfinite(o.pose.x_m) && std::isfinite(o.pose.y_m) &&
            !near_floor({o.pose.x_m, o.pose.y_m})) {
            p.push_back("object " + std::to_string(o.id) + beyond);
        }
    }
    std::size_t environment_triangles = 0;
    for (const EnvironmentMesh& e : environment) {
        if (!e.mesh_world) continue;  // not loaded (parsed without its folder)
        environment_triangles += e.mesh_world->num_triangles();
        Eigen::Vector3d lo, hi;
        mesh_bounds(*e.mesh_world, lo, hi);
        if (!near_floor(lo.head<2>()) || !near_floor(hi.head<2>()))
            p.push_back("environment mesh '" + e.mesh_file + "': a part" + beyond);
    }
    if (environment_triangles > kMaxEnvironmentTriangles)
        p.push_back("environment: at most 5000000 triangles in all (decimate the scan)");
    for (const Walker& w : walkers) {
        if (std::any_of(w.route_m.begin(), w.route_m.end(),
                        [&](const Eigen::Vector2d& q) { return !near_floor(q); })) {
            p.push_back("walker: a route point" + beyond);
        }
    }
    for (const Wall& w : walls) {
        if (!(w.thickness_m > 0.0 && w.height_m > 0.0))
            p.push_back("wall: thickness_m and height_m must be > 0");
    }
    for (const Pillar& pl : pillars) {
        if (!(pl.size_m.x() > 0.0 && pl.size_m.y() > 0.0 && pl.height_m > 0.0))
            p.push_back("pillar: size_m and height_m must be > 0");
    }
    return p;
}

}  // namespace makeway::sim
