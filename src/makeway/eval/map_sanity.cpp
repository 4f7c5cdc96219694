#include "makeway/eval/map_sanity.hpp"

#include <algorithm>

namespace makeway::eval {

void MapSanity::add(const MapSanity& o) {
    object_frames += o.object_frames;
    outside_room += o.outside_room;
    above_floor += o.above_floor;
    fast_unpushed += o.fast_unpushed;
    max_speed_mps = std::max(max_speed_mps, o.max_speed_mps);
    max_bottom_m = std::max(max_bottom_m, o.max_bottom_m);
}

MapSanity check_map(const std::vector<ObjectEstimate>& objects, const sim::Scene& scene,
                    const std::vector<sim::ObjectModel>& models, double t_s,
                    const MapSanityParams& p) {
    MapSanity s;
    std::vector<std::vector<sim::ObjectState>> truth;  // only when a fast object needs it
    for (const ObjectEstimate& o : objects) {
        ++s.object_frames;
        const Eigen::Vector3d& c = o.box_world.centre_m;
        if (!scene.on_floor(c.head<2>())) ++s.outside_room;
        const double bottom = c.z() - o.box_world.size_m.z() / 2;
        s.max_bottom_m = std::max(s.max_bottom_m, bottom);
        if (bottom > p.max_floor_gap_m) ++s.above_floor;
        const double speed = o.velocity_mps.norm();
        s.max_speed_mps = std::max(s.max_speed_mps, speed);
        if (speed <= p.max_speed_mps) continue;
        if (truth.empty()) {
            for (double back : p.pushed_lookback_s)
                truth.push_back(sim::object_states_at(scene, models, std::max(0.0, t_s - back)));
        }
        const bool pushed = std::any_of(
            truth.begin(), truth.end(), [&](const std::vector<sim::ObjectState>& states) {
                return std::any_of(states.begin(), states.end(), [&](const sim::ObjectState& t) {
                    return (t.box_world.centre_m - c).head<2>().norm() < p.pushed_radius_m &&
                           t.velocity_mps.norm() >= p.pushed_speed_mps;
                });
            });
        if (!pushed) ++s.fast_unpushed;
    }
    return s;
}

}  // namespace makeway::eval
