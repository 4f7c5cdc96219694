#include <gtest/gtest.h>

#include "../sim/sim_test_util.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::perception {
namespace {

// The robot drives at 0.75 m/s while turning; every table point of every sweep, accumulated into
// the newest frame and mapped back to the world, must lie on the table.
TEST(Accumulator, StaticObjectLandsInTheSamePlaceFromEverySweep) {
    sim::Scene s = sim::testing_util::box_room(6.0);
    sim::SceneObject table;
    table.id = 9;
    table.cls = ObjectClass::kTable;
    table.style = "rect_table";
    table.pose = {2.5, 0.5, 0.4};
    s.objects.push_back(table);
    const sim::ObjectModel model = sim::model_of(table);
    sim::World world(s, {model});
    TriangleMesh placed = model.mesh_object;
    sim::transform_mesh(placed, lift_to_3d(table.pose));
    auto pose_at = [](double t) {
        return make_T_xyz_yaw({-2.0 + 0.75 * t, 0.2 * t, 0.45}, 0.4 * t);
    };
    sim::LidarParams lidar;
    lidar.range_noise_m = 0.0;
    lidar.azimuth_step_deg = 0.4;

    for (bool deskew : {true, false}) {
        KeyframeAccumulator acc({.window = 5, .deskew = deskew});
        std::vector<std::size_t> per_sweep;
        for (int k = 0; k < 6; ++k) {  // 6 sweeps: the first leaves the window
            StampedSweep sw;
            sw.stamp_s = 0.1 * k;
            sw.points_sensor = sim::simulate_sweep(world, lidar, pose_at, sw.stamp_s, 1, k);
            sw.T_world_sensor_start = pose_at(sw.stamp_s);
            sw.T_world_sensor_end = pose_at(sw.stamp_s + 0.1);
            acc.add(sw);
        }
        ASSERT_TRUE(acc.full());
        Isometry3 T_world_kf;
        const PointCloud kf = acc.keyframe(&T_world_kf);
        EXPECT_TRUE(T_world_kf.isApprox(pose_at(0.5), 1e-12));
        double worst = 0.0;
        std::size_t n = 0;
        for (std::size_t i = 0; i < kf.size(); i += 3) {
            if (kf.instance[i] != 9) continue;
            ++n;
            EXPECT_GE(kf.time_s[i],
                      -0.4f - 1e-6f);  // times relative to the keyframe: 4 sweeps back at most
            worst = std::max(worst, sim::testing_util::mesh_distance(
                                        placed, T_world_kf * kf.xyz[i].cast<double>()));
        }
        EXPECT_GT(n, 300u);
        if (deskew) {
            EXPECT_LT(worst, 0.005);  // exact poses, no noise: only float rounding
        } else {
            EXPECT_GT(worst, 0.02);  // motion within a sweep smears the object without de-skewing
        }
    }
}

TEST(Accumulator, EmptyAndSingleSweep) {
    KeyframeAccumulator acc;
    EXPECT_TRUE(acc.keyframe().empty());
    StampedSweep sw;
    sw.points_sensor.xyz = {{1, 0, 0}};
    sw.T_world_sensor_start = sw.T_world_sensor_end = make_T_xyz_yaw({5, 0, 0}, 0.0);
    acc.add(sw);
    EXPECT_FALSE(acc.full());
    const PointCloud kf = acc.keyframe();
    ASSERT_EQ(kf.size(), 1u);
    EXPECT_EQ(kf.xyz[0], Eigen::Vector3f(1, 0, 0));
}

}  // namespace
}  // namespace makeway::perception
