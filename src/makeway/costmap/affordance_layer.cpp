#include "makeway/costmap/affordance_layer.hpp"

namespace makeway::costmap {

void AffordanceLayer::update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) {
    window.expand(previous_);  // where the old zones were: cleared by the master reset
    objects_.clear();
    GridWindow current;
    for (const ObjectEstimate& o : input.objects) {
        if (o.existence < params_.min_existence) continue;
        objects_.push_back(o);
        Eigen::Vector2d lo, hi;
        zone_bounds(o, params_, lo, hi);
        current.expand(master.window_of(lo, hi));
    }
    window.expand(current);
    previous_ = current;
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
