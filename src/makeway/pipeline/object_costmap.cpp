#include "makeway/pipeline/object_costmap.hpp"

#include <algorithm>
#include <memory>

#include "makeway/common/param_table.hpp"
#include "makeway/costmap/affordance_layer.hpp"
#include "makeway/costmap/inflation_layer.hpp"
#include "makeway/costmap/obstacle_layer.hpp"
#include "makeway/costmap/static_layer.hpp"

namespace makeway::pipeline {

ObjectCostmap::ObjectCostmap(const Costmap& static_map, const NavigatorParams& params)
    : layered_(Costmap(static_map.origin_m, static_map.resolution_m, static_map.width,
                       static_map.height)) {
    throw_if_problems(params.validate());
    layered_.add_layer(std::make_unique<costmap::StaticLayer>(static_map));
    layered_.add_layer(std::make_unique<costmap::ObstacleLayer>(static_map, params.obstacle));
    if (params.affordance_layer)
        layered_.add_layer(std::make_unique<costmap::AffordanceLayer>(params.affordance));
    costmap::InflationParams inflation = params.inflation;
    inflation.inflation_radius_m =
        std::max(inflation.inflation_radius_m, inflation.inscribed_radius_m);
    inflation.threads = params.obstacle.threads;  // costmap.threads: the rays and the distances
    layered_.add_layer(std::make_unique<costmap::InflationLayer>(inflation));
}

void ObjectCostmap::update(const PointCloud* points_world, const Eigen::Vector3d& sensor_world_m,
                           const std::vector<ObjectEstimate>& objects) {
    costmap::LayerInput input;
    input.points_world = points_world;
    input.sensor_world_m = sensor_world_m;
    input.objects = objects;
    layered_.update(input);
}

}  // namespace makeway::pipeline
