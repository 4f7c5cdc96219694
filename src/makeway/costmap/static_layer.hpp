#pragma once
// The known building: walls and pillars (or a map_server map) as lethal cells, written once.
#include <memory>

#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

class StaticLayer : public Layer {
  public:
    /// `map` has the master's geometry; lethal/unknown cells are copied, the rest ignored.
    explicit StaticLayer(Costmap map) : map_(std::move(map)) {}
    std::string name() const override { return "static"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;
    const Costmap& grid() const { return map_; }

  private:
    Costmap map_;
    bool written_ = false;
};

/// Rasterises filled rectangles (centre, size, yaw) as lethal into a grid of the given geometry.
void fill_rectangle(Costmap& grid, const Eigen::Vector2d& centre_m, const Eigen::Vector2d& size_m,
                    double yaw_rad, std::uint8_t value);

}  // namespace makeway::costmap
