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

GridWindow AffordanceLayer::zone_window(const Costmap& master, const ObjectEstimate& o) const {
    Eigen::Vector2d lo, hi;
    zone_bounds(o, params_, lo, hi);
    const Eigen::Vector2d margin = Eigen::Vector2d::Constant(params_.margin_m);
    return master.window_of(lo - margin, hi + margin);
}

void AffordanceLayer::update_bounds(const Costmap& master, const LayerInput& input,
                                    GridWindow& window) {
    std::vector<ObjectEstimate> kept;
    for (const ObjectEstimate& o : input.objects) {
        if (o.existence >= params_.min_existence) kept.push_back(o);
    }
    // Only the zones that appeared or vanished need rewriting (a moved object is both): the master
    // is reset inside the window, and every zone overlapping it is written again (update_costs).
    // The map hands the same objects sweep after sweep between keyframes; their zones stand.
    // A patch is of one master geometry: another (a new map) computes every zone again.
    if (master.origin_m != patch_origin_m_ || master.resolution_m != patch_resolution_m_) {
        for (Patch& patch : patches_) patch.cost.clear();
        patch_origin_m_ = master.origin_m, patch_resolution_m_ = master.resolution_m;
    }
    std::vector<bool> matched(objects_.size(), false);
    std::vector<Patch> patches(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
        const ObjectEstimate& o = kept[k];
        bool found = false;
        for (std::size_t i = 0; i < objects_.size() && !found; ++i) {
            if (!matched[i] && same_zone(o, objects_[i])) {
                matched[i] = found = true;
                patches[k] = std::move(patches_[i]);
            }
        }
        if (!found) window.expand(zone_window(master, o));
    }
    for (std::size_t i = 0; i < objects_.size(); ++i) {
        if (!matched[i]) window.expand(zone_window(master, objects_[i]));
    }
    objects_ = std::move(kept);
    patches_ = std::move(patches);
}

void AffordanceLayer::update_costs(Costmap& master, const GridWindow& window) {
    for (std::size_t k = 0; k < objects_.size(); ++k) {
        const ObjectEstimate& o = objects_[k];
        Patch& patch = patches_[k];
        if (patch.cost.empty()) {
            patch.window = zone_window(master, o);
            const GridWindow& w = patch.window;
            if (w.empty()) continue;
            patch.cost.resize(static_cast<std::size_t>(w.x1 - w.x0) * (w.y1 - w.y0));
            std::uint8_t* c = patch.cost.data();
            for (int y = w.y0; y < w.y1; ++y)
                for (int x = w.x0; x < w.x1; ++x)
                    *c++ = zone_cost(o, params_, master.centre_of(x, y));
        }
        const GridWindow& w = patch.window;
        const int stride = w.x1 - w.x0;
        for (int y = std::max(w.y0, window.y0); y < std::min(w.y1, window.y1); ++y) {
            for (int x = std::max(w.x0, window.x0); x < std::min(w.x1, window.x1); ++x) {
                const std::uint8_t c =
                    patch.cost[static_cast<std::size_t>(y - w.y0) * stride + (x - w.x0)];
                std::uint8_t& m = master.at(x, y);
                if (c != cost::kFree && (c > m || m == cost::kUnknown)) m = c;
            }
        }
    }
}

}  // namespace makeway::costmap
