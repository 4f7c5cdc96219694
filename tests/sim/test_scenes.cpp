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

// How each usage profile moves a chair, in the chair's own frame at its base pose, over the
// chairs of several sessions that do not belong to a moved table.
TEST(SceneGenerator, UsageProfilesMoveChairsTheirOwnWay) {
    struct Motions {
        int chairs = 0, moved = 0, back = 0, sideways_turned = 0, forward = 0;
    };
    const auto motions_of = [](UsageProfile usage) {
        Motions m;
        for (std::uint64_t seed : {3u, 4u}) {
            const Scene base = generate_scene({.seed = seed, .usage = usage});
            EXPECT_EQ(base.usage, usage);
            for (int k = 1; k <= 4; ++k) {
                const Scene s = make_session(base, k);
                for (std::size_t i = 0; i < base.objects.size(); ++i) {
                    const SceneObject& o = base.objects[i];
                    if (o.cls != ObjectClass::kChair) continue;
                    // Chairs at a table that moved moved with it: left out.
                    bool table_moved = false;
                    for (std::size_t j = 0; j < base.objects.size(); ++j) {
                        table_moved |= base.objects[j].id == o.table_id &&
                                       (s.objects[j].pose.x_m != base.objects[j].pose.x_m ||
                                        s.objects[j].pose.y_m != base.objects[j].pose.y_m);
                    }
                    if (table_moved) continue;
                    const Pose2 d = between(o.pose, s.objects[i].pose);
                    ++m.chairs;
                    if (std::hypot(d.x_m, d.y_m) < 1e-9) continue;
                    ++m.moved;
                    m.back += d.x_m < -0.34 && std::abs(d.y_m) < 1e-9 &&
                              std::abs(d.yaw_rad) < deg_to_rad(15);
                    m.sideways_turned += std::abs(d.y_m) >= 0.25 &&
                                         std::abs(d.yaw_rad) >= deg_to_rad(50) &&
                                         d.y_m * d.yaw_rad > 0;  // turned toward the side it went
                    m.forward += d.x_m > 0.0;
                }
            }
        }
        return m;
    };
    const Motions pulled = motions_of(UsageProfile::kPulledBack);
    ASSERT_GT(pulled.chairs, 40);
    EXPECT_EQ(pulled.back, pulled.moved);  // all straight back 0.35-0.9 m, nearly unturned
    EXPECT_GT(pulled.moved, pulled.chairs / 2);
    const Motions sideways = motions_of(UsageProfile::kSideways);
    EXPECT_EQ(sideways.sideways_turned, sideways.moved);
    EXPECT_EQ(sideways.forward, 0);
    EXPECT_GT(sideways.moved, sideways.chairs / 3);
    const Motions other = motions_of(UsageProfile::kDefault);
    EXPECT_GT(other.forward, 0);  // the default pushes some in
    EXPECT_EQ(other.sideways_turned, 0);
    EXPECT_EQ(parse_usage_profile("tables_nudged"), UsageProfile::kTablesNudged);
    EXPECT_EQ(to_string(UsageProfile::kSideways), "sideways");
    EXPECT_FALSE(parse_usage_profile("pulled back").has_value());
}

TEST(SceneGenerator, NudgedTablesTakeTheirChairsAlong) {
    const Scene base = generate_scene({.seed = 5, .usage = UsageProfile::kTablesNudged});
    int tables_moved = 0;
    for (int k = 1; k <= 3; ++k) {
        const Scene s = make_session(base, k);
        for (std::size_t j = 0; j < base.objects.size(); ++j) {
            const SceneObject& t = base.objects[j];
            if (t.cls != ObjectClass::kTable) continue;
            const Pose2 d = between(t.pose, s.objects[j].pose);
            if (std::hypot(d.x_m, d.y_m) < 1e-9) continue;
            ++tables_moved;
            EXPECT_NEAR(std::abs(d.x_m), std::clamp(std::abs(d.x_m), 0.2, 0.6), 1e-9);
            EXPECT_NEAR(d.y_m, 0.0, 1e-9);  // along its length
            // Its chairs keep their place relative to it (up to the chair's own move).
            for (std::size_t i = 0; i < base.objects.size(); ++i) {
                if (base.objects[i].table_id != t.id) continue;
                const Pose2 before = between(t.pose, base.objects[i].pose);
                const Pose2 after = between(s.objects[j].pose, s.objects[i].pose);
                EXPECT_LT(std::hypot(after.x_m - before.x_m, after.y_m - before.y_m), 0.5);
            }
        }
    }
    EXPECT_GT(tables_moved, 0);
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
