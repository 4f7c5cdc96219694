#include <gtest/gtest.h>

#include <cmath>

#include "../planning/monitor_test_util.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/common/polygon2d.hpp"
#include "makeway/pipeline/online_system.hpp"

namespace makeway::pipeline {
namespace {

// A pedestal table's foot (a disk of radius 0.27 m, 3 cm high) 8 cm ahead of a robot that is told
// to drive through it. Its sweeps never show the foot (below the lowest beam this close):
// only the table's CAD model, through ObjectEstimate::parts_world, says where it is.
struct Drive {
    double closest_m = INFINITY;  ///< the footprint's least distance to the foot's edge
};

Drive drive_at_the_foot(bool object_parts, double drop_object_after_s) {
    const Eigen::Vector2d foot_centre(0.254 + 0.08 + 0.27, 0.0);
    const double foot_r = 0.27;
    ObjectEstimate table;
    table.id = 7;
    table.cls = ObjectClass::kTable;
    table.box_world.centre_m = {foot_centre.x(), 0.0, 0.375};
    table.box_world.size_m = {1.0, 1.0, 0.75};
    Polygon2 foot;
    for (int k = 0; k < 32; ++k) {
        const double a = 2.0 * kPi * k / 32;
        foot.push_back(foot_centre + foot_r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    table.parts_world = {foot};

    const Costmap map({-5.0, -5.0}, 0.05, 200, 200, cost::kFree);
    NavigatorParams params;
    params.affordance_layer = false;      // the costmap knows nothing of the table either
    params.monitor = planning::jackal();  // the robot footprint_distance measures
    params.monitor.object_parts = object_parts;
    Controller controller(map, params);
    controller.set_route({{3.0, 0.0}});
    const PointCloud nothing;
    Pose2 pose{0.0, 0.0, 0.0};
    double v = 0.0, w = 0.0;
    Drive out;
    for (int k = 0; k < 80; ++k) {  // 8 s at 10 Hz
        const double t = 0.1 * k;
        std::vector<ObjectEstimate> objects;
        if (t < drop_object_after_s) objects.push_back(table);  // then the map drops it
        const Controller::Step s = controller.step(
            {t, pose, v, w, &nothing, Eigen::Vector3d(pose.x_m, pose.y_m, 0.45), objects});
        v = s.command.v_mps, w = s.command.w_radps;
        pose = {pose.x_m + 0.1 * v * std::cos(pose.yaw_rad),
                pose.y_m + 0.1 * v * std::sin(pose.yaw_rad), wrap_angle(pose.yaw_rad + 0.1 * w)};
        out.closest_m =
            std::min(out.closest_m, planning::footprint_distance(pose, foot_centre) - foot_r);
    }
    return out;
}

TEST(Controller, AnObjectsCadPartsHoldTheRobotAtAFootItsSweepsDoNotShow) {
    const Drive blind = drive_at_the_foot(false, INFINITY);
    EXPECT_LT(blind.closest_m, 0.0) << "without the parts the robot drives onto the foot";
    const Drive held = drive_at_the_foot(true, INFINITY);
    EXPECT_GT(held.closest_m, 0.0);
    EXPECT_LT(held.closest_m, 0.08);  // it drove up to the foot, and stopped short of it
}

TEST(Controller, AnObjectTheMapDropsKeepsItsPartsForTheBlindMemory) {
    // The map drops the table after 1 s (too close to be detected): its foot still holds the
    // robot for blind_memory_s (10 s, longer than this drive).
    const Drive dropped = drive_at_the_foot(true, 1.0);
    EXPECT_GT(dropped.closest_m, 0.0);
}

}  // namespace
}  // namespace makeway::pipeline
