#pragma once
// The object-aware costmap of the online system, nav2's layered costmap with the paper's layer:
// static (the prebuilt map of walls), obstacle (LiDAR returns), affordance (each object's
// class-specific zone), inflation last. The Navigator plans on it; `makeway run` and the ROS node
// publish it.
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/costmap/layered_costmap.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace makeway::pipeline {

class ObjectCostmap {
  public:
    /// The grid is `static_map`'s (origin, resolution, size). Throws std::invalid_argument listing
    /// every problem of `params`.
    ObjectCostmap(const Costmap& static_map, const NavigatorParams& params);

    /// One sweep: `points_world` (may be null: only the objects change) seen from `sensor_world_m`,
    /// and the object map after it.
    void update(const PointCloud* points_world, const Eigen::Vector3d& sensor_world_m,
                const std::vector<ObjectEstimate>& objects);

    const Costmap& master() const { return layered_.master(); }

  private:
    costmap::LayeredCostmap layered_;
};

}  // namespace makeway::pipeline
