#pragma once
// The master costmap and its layers (static, obstacle, affordance, then inflation last).
#include <memory>
#include <vector>

#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

struct UpdateResult {
    GridWindow window;  ///< the cells rewritten
};

class LayeredCostmap {
  public:
    explicit LayeredCostmap(Costmap geometry) : master_(std::move(geometry)) {}
    /// Layers update in the order added; inflation belongs last.
    void add_layer(std::unique_ptr<Layer> layer) { layers_.push_back(std::move(layer)); }
    UpdateResult update(const LayerInput& input);
    const Costmap& master() const { return master_; }
    const std::vector<std::unique_ptr<Layer>>& layers() const { return layers_; }

  private:
    Costmap master_;
    std::vector<std::unique_ptr<Layer>> layers_;
};

}  // namespace makeway::costmap
