#include "makeway/costmap/affordance_layer.hpp"

#include <algorithm>

namespace makeway::costmap {
namespace {

// Everything a zone depends on (affordance.hpp: class, footprint, pose); existence only through
// min_existence, which decides whether the object is kept at all.
bool same_zone(const ObjectEstimate& a, const ObjectEstimate& b) {
    return a.cls == b.cls && a.box_world.centre_m.head<2>() == b.box_world.centre_m.head<2>() &&
           a.box_world.size_m.head<2>() == b.box_world.size_m.head<2>() &&
           a.box_world.yaw_rad == b.box_world.yaw_rad;
}

}  // namespace

void AffordanceLayer::update_bounds(const Costmap& master, const LayerInput& input,
                                    GridWindow& window) {
    std::vector<ObjectEstimate> kept;
    for (const ObjectEstimate& o : input.objects) {
        if (o.existence >= params_.min_existence) kept.push_back(o);
    }
    // Only the zones that appeared or vanished need rewriting (a moved object is both): the master
    // is reset inside the window, and every zone overlapping it is written again (update_costs).
    // The map hands the same objects sweep after sweep between keyframes; their zones stand.
    auto bounds_of = [&](const ObjectEstimate& o) {
        Eigen::Vector2d lo, hi;
        zone_bounds(o, params_, lo, hi);
        return master.window_of(lo, hi);
    };
    std::vector<bool> matched(objects_.size(), false);
    for (const ObjectEstimate& o : kept) {
        bool found = false;
        for (std::size_t i = 0; i < objects_.size() && !found; ++i) {
            if (!matched[i] && same_zone(o, objects_[i])) matched[i] = found = true;
        }
        if (!found) window.expand(bounds_of(o));
    }
    for (std::size_t i = 0; i < objects_.size(); ++i) {
        if (!matched[i]) window.expand(bounds_of(objects_[i]));
    }
    objects_ = std::move(kept);
}

void AffordanceLayer::update_costs(Costmap& master, const GridWindow& window) {
    for (const ObjectEstimate& o : objects_) {
        Eigen::Vector2d lo, hi;
        zone_bounds(o, params_, lo, hi);
        const GridWindow w = master.window_of(lo, hi);
        for (int y = std::max(w.y0, window.y0); y < std::min(w.y1, window.y1); ++y) {
            for (int x = std::max(w.x0, window.x0); x < std::min(w.x1, window.x1); ++x) {
                const std::uint8_t c = zone_cost(o, params_, master.centre_of(x, y));
                std::uint8_t& m = master.at(x, y);
                if (c != cost::kFree && (c > m || m == cost::kUnknown)) m = c;
            }
        }
    }
}

}  // namespace makeway::costmap
