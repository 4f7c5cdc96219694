#include "makeway/costmap/layered_costmap.hpp"

namespace makeway::costmap {

UpdateResult LayeredCostmap::update(const LayerInput& input) {
    UpdateResult r;
    for (auto& layer : layers_) layer->update_bounds(master_, input, r.window);
    r.window = r.window.clipped(master_.width, master_.height);
    if (r.window.empty()) return r;
    for (int y = r.window.y0; y < r.window.y1; ++y) {
        std::fill_n(&master_.at(r.window.x0, y), r.window.x1 - r.window.x0, cost::kFree);
    }
    for (auto& layer : layers_) layer->update_costs(master_, r.window);
    return r;
}

}  // namespace makeway::costmap
