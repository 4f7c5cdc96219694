#pragma once
// The object affordance layer: each object's class-specific zone (affordance.hpp), aligned with its
// pose. The update window covers the zones that changed (an object that appeared, vanished, moved
// or changed class or size: its old zone and its new one), so zones left behind are cleared and
// zones that stand are not rewritten every sweep.
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
    std::vector<ObjectEstimate>
        objects_;  ///< the kept objects (existence >= min_existence) of the last update
};

}  // namespace makeway::costmap
