#include "makeway/pipeline/system_params.hpp"

#include <algorithm>
#include <stdexcept>

#include "makeway/perception/param_tables.hpp"
#include "makeway/pipeline/param_tables.hpp"

namespace makeway::pipeline {
namespace {

void add(std::vector<std::string>& out, const std::string& prefix,
         const std::vector<std::string>& problems) {
    for (const std::string& p : problems) out.push_back(prefix + "." + p);
}

}  // namespace

void apply_robot(const RobotDescription& robot, SystemParams& params,
                 const Isometry3* T_base_sensor) {
    params.T_base_sensor = T_base_sensor ? *T_base_sensor : robot.T_robot_sensor();
    NavigatorParams& n = params.navigator;
    n.inflation.inscribed_radius_m = robot.inscribed_radius_m();
    n.inflation.inflation_radius_m = robot.circumscribed_radius_m();
    n.obstacle.body = robot.body();  // what the robot can hit is what the costmap marks
    n.dwa.footprint_length_m = robot.length_m;
    n.dwa.footprint_width_m = robot.width_m;
    n.dwa.max_v_mps = std::min(n.dwa.max_v_mps, robot.max_v_mps);
    n.dwa.max_w_radps = robot.max_w_radps;
    n.dwa.acc_v_mps2 = robot.max_acc_mps2;
    n.dwa.acc_w_radps2 = robot.max_ang_acc_radps2;
    n.monitor.apply_robot(robot);
    n.monitor.sensor_height_m =
        params.T_base_sensor.translation().z();  // the blind ring is the mounted sensor's
}

std::vector<std::string> KeyframeParams::validate() const {
    return keyframe_table().problems(*this);
}

std::vector<std::string> NavigatorParams::validate() const {
    std::vector<std::string> p;
    add(p, "obstacle", obstacle.validate());
    add(p, "inflation", inflation.validate());
    add(p, "affordance", affordance.validate());
    add(p, "astar", astar.validate());
    add(p, "dwa", dwa.validate());
    add(p, "collision_monitor", monitor.validate());
    for (std::string& m : validate_policy()) p.push_back(std::move(m));
    return p;
}

std::vector<std::string> NavigatorParams::validate_policy() const {
    return navigator_policy_table().problems(*this);
}

std::vector<std::string> SystemParams::validate() const {
    std::vector<std::string> p;
    if (!T_base_sensor.matrix().allFinite()) p.push_back("T_base_sensor must be finite");
    if (lidar_odometry_enabled) add(p, "lidar_odometry", lidar_odometry.validate());
    add(p, "perception", keyframe.validate());  // its keys are the perception section's
    add(p, "verification", verify.validate());
    add(p, "verification.shapes", shapes.validate());
    add(p, "verification.back_yaw", back_yaw.validate());
    add(p, "tracking", tracker.validate());
    add(p, "navigation", navigator.validate());
    return p;
}

}  // namespace makeway::pipeline
