#include "io/nav_config.hpp"

#include <algorithm>

namespace makeway::io {

eval::NavParams nav_params(const SimConfig& config) {
    eval::NavParams p;
    p.lidar = config.lidar;
    p.robot = config.robot;
    p.odometry = config.odometry;
    p.system = online_system_params(config);  // navigation sets each method's inflation radius
    // The simulated robot carries the simulated LiDAR: its collision monitor never assumes a lower
    // beam than that sensor has. Near the robot it remembers what the sensor can no longer see; a
    // VLP-16 sees 15 deg down, not a VLP-32C's 25, and a monitor told -25 forgot chair legs it was
    // closing in on (2 robot-caused contacts in 25 scenes, none once told -15).
    double& lowest = p.system.navigator.monitor.lowest_beam_deg;
    lowest = std::max(lowest, config.lidar.elevations_deg().front());
    p.seed = config.simulation.seed;
    return p;
}

}  // namespace makeway::io
