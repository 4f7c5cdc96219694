#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::sim {
namespace {

std::vector<OrientedBox> boxes_of(const Scene& s) {
    std::vector<OrientedBox> out;
    for (const auto& o : s.objects)
        out.push_back(model_of(o).box_object.transformed(lift_to_3d(o.pose)));
    return out;
}

TEST(SceneGenerator, ScenesAreValidCollisionFreeAndNavigable) {
    for (Density d : {Density::kSparse, Density::kMedium, Density::kDense}) {
        for (std::uint64_t seed = 0; seed < 3; ++seed) {
            const Scene s = generate_scene({.seed = seed, .density = d});
            EXPECT_EQ(s.validate(), std::vector<std::string>{});
            EXPECT_TRUE(is_navigable(s, RobotParams{})) << to_string(d) << " " << seed;
            const auto boxes = boxes_of(s);
            for (std::size_t i = 0; i < boxes.size(); ++i) {
                for (std::size_t j = i + 1; j < boxes.size(); ++j) {
                    const bool related = s.objects[i].table_id == s.objects[j].id ||
                                         s.objects[j].table_id == s.objects[i].id;
                    if (!related) {
                        EXPECT_EQ(iou_bev(boxes[i], boxes[j]), 0.0) << i << " " << j;
                    }
                }
            }
        }
    }
}

TEST(SceneGenerator, DensityGrowsTheClutter) {
    std::size_t sparse = 0, dense = 0;
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
        sparse += generate_scene({.seed = seed, .density = Density::kSparse}).objects.size();
        dense += generate_scene({.seed = seed, .density = Density::kDense}).objects.size();
    }
    EXPECT_GT(dense, 2 * sparse);
}

TEST(SceneGenerator, StudySpaceHasTwelveTablesAndTwentyTwoChairs) {
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
        const Scene s = generate_scene({.seed = seed, .layout = Layout::kStudySpace});
        int tables = 0, chairs = 0;
        for (const auto& o : s.objects) (o.cls == ObjectClass::kTable ? tables : chairs)++;
        EXPECT_EQ(tables, 12);
        EXPECT_EQ(chairs, 22);
    }
}

TEST(SceneGenerator, SameSeedSameScene) {
    const Scene a = generate_scene({.seed = 7});
    const Scene b = generate_scene({.seed = 7});
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (std::size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].pose.x_m, b.objects[i].pose.x_m);
        EXPECT_EQ(a.objects[i].model_seed, b.objects[i].model_seed);
    }
}

TEST(SceneDynamics, ChairPushingMovesAlongTheForwardAxisOnly) {
    Scene s = generate_scene({.seed = 2, .density = Density::kDense});
    ASSERT_FALSE(s.pushers.empty());
    for (const ChairPusher& p : s.pushers) {
        const auto k = static_cast<std::size_t>(
            std::find_if(s.objects.begin(), s.objects.end(),
                         [&](const auto& o) { return o.id == p.chair_id; }) -
            s.objects.begin());
        const Pose2 base = s.objects[k].pose;
        const Eigen::Vector2d forward(std::cos(base.yaw_rad), std::sin(base.yaw_rad));
        for (double t = 0; t < 20; t += 0.37) {
            Eigen::Vector2d v;
            const Pose2 q = object_pose_at(s, k, t, &v);
            const Eigen::Vector2d d(q.x_m - base.x_m, q.y_m - base.y_m);
            EXPECT_NEAR(d.dot(Eigen::Vector2d(-forward.y(), forward.x())), 0.0, 1e-12);
            EXPECT_LE(d.dot(forward), 1e-12);
            EXPECT_GE(d.dot(forward), -p.pull_m - 1e-12);
            EXPECT_EQ(q.yaw_rad, base.yaw_rad);
            EXPECT_NEAR(v.dot(Eigen::Vector2d(-forward.y(), forward.x())), 0.0, 1e-12);
        }
    }
}

TEST(SceneGenerator, SessionsMoveFurnitureButKeepTheBuilding) {
    const Scene base = generate_scene({.seed = 3});
    const Scene s1 = make_session(base, 1);
    ASSERT_EQ(s1.objects.size(), base.objects.size());
    EXPECT_EQ(s1.walls.size(), base.walls.size());
    int moved = 0;
    for (std::size_t i = 0; i < base.objects.size(); ++i) {
        moved += std::hypot(s1.objects[i].pose.x_m - base.objects[i].pose.x_m,
                            s1.objects[i].pose.y_m - base.objects[i].pose.y_m) > 0.01;
    }
    EXPECT_GT(moved, 0);
    EXPECT_TRUE(is_navigable(s1, RobotParams{}));
}

TEST(Sequence, RobotDrivesTheRouteWithoutCollisions) {
    const Scene s = generate_scene({.seed = 0, .density = Density::kSparse});
    SequenceParams p;
    p.lidar.azimuth_step_deg = 2.0;  // a coarse sensor keeps the test fast
    const std::vector<ObjectModel> models = models_of(s);
    const CollisionChecker checker(s, models, p.robot);
    const auto route = drive_route(s, checker, p.robot);
    ASSERT_TRUE(route.has_value());
    SequenceSimulator sim(s, *route, p);
    int frames = 0;
    double last_x = -1e9;
    while (!sim.reached_goal() && frames < 1500) {
        const SimFrame f = sim.next();
        EXPECT_FALSE(f.collided) << "frame " << f.index << " at " << f.true_pose.x_m << " "
                                 << f.true_pose.y_m;
        EXPECT_GT(f.points_sensor.size(), 1000u);
        EXPECT_EQ(f.objects.size(), s.objects.size());
        last_x = f.true_pose.x_m;
        ++frames;
    }
    EXPECT_TRUE(sim.reached_goal());
    EXPECT_NEAR(last_x, s.goal.x_m, 0.3);
}

}  // namespace
}  // namespace makeway::sim
