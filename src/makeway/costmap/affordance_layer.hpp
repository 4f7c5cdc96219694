#pragma once
// The object affordance layer: each object's class-specific zone (affordance.hpp), aligned with its
// pose. Zones of objects that moved or vanished are cleared because the update window always covers
// the previous zones as well as the new ones.
#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

class AffordanceLayer : public Layer {
public:
    explicit AffordanceLayer(const AffordanceParams& params) : params_(params) {}
    std::string name() const override { return "affordance"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;

private:
    AffordanceParams params_;
    std::vector<ObjectEstimate> objects_;
    GridWindow previous_;
};

}  // namespace makeway::costmap
