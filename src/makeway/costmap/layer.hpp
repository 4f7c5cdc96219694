#pragma once
// The nav2 layered-costmap contract: every update, each layer first grows a shared window with the
// cells it needs to change (update_bounds), the master grid is reset inside that window, then each
// layer writes its costs inside the window only (update_costs). Layers merge by max.
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::costmap {

/// What one update sees.
struct LayerInput {
    const PointCloud* points_world =
        nullptr;  ///< the latest sweep in the world frame (may be null)
    Eigen::Vector3d sensor_world_m = Eigen::Vector3d::Zero();
    std::vector<ObjectEstimate> objects;
};

class Layer {
  public:
    virtual ~Layer() = default;
    virtual std::string name() const = 0;
    /// Grows `window` by the cells this update changes.
    virtual void update_bounds(const Costmap& master, const LayerInput& input,
                               GridWindow& window) = 0;
    /// Writes this layer's costs into master, inside window only, merging by max.
    virtual void update_costs(Costmap& master, const GridWindow& window) = 0;
};

}  // namespace makeway::costmap
