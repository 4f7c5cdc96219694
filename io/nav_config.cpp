#include "io/nav_config.hpp"

namespace makeway::io {

eval::NavParams nav_params(const SimConfig& config) {
    eval::NavParams p;
    p.lidar = config.lidar;
    p.robot = config.robot;
    p.odometry = config.odometry;
    p.system = online_system_params(config);  // navigation sets each method's inflation radius
    p.seed = config.simulation.seed;
    return p;
}

}  // namespace makeway::io
