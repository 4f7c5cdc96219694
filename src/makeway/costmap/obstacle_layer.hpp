#pragma once
// Obstacles seen by the LiDAR: cells holding a return between min_height_m and max_height_m are
// marked lethal; every ray (to returns below max_height_m, ground included) clears the cells it
// crosses. Marks persist until a ray clears them, so objects that moved leave no stale cost.
#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

struct ObstacleLayerParams {
    double min_height_m = 0.05;      ///< returns below are floor
    double max_height_m = 0.6;       ///< returns above cannot touch the robot (table tops at 0.75 m)
    double mark_range_m = 6.0;
    double clear_range_m = 8.0;
    std::vector<std::string> validate() const;
};

class ObstacleLayer : public Layer {
public:
    ObstacleLayer(const Costmap& geometry, const ObstacleLayerParams& params);
    std::string name() const override { return "obstacle"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;
    const Costmap& grid() const { return grid_; }

private:
    ObstacleLayerParams params_;
    Costmap grid_;
    std::vector<std::uint8_t> endpoint_;  ///< per cell, during one update: 0 none, 1 clear-only, 2 mark (zero between updates)
    std::vector<int> cells_;              ///< the cells with an endpoint in this update
};

}  // namespace makeway::costmap
