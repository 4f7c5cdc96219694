#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "makeway/common/angles.hpp"
#include "makeway/eval/navigation.hpp"
#include "makeway/eval/object_source.hpp"
#include "makeway/sim/robot.hpp"

namespace makeway::eval {
namespace {

// A 10 x 5 m room with a table and its chair between start and goal.
sim::Scene corridor_with_table() {
    sim::Scene s;
    s.name = "table_room";
    s.floor_min_m = {-5.5, -3.0};
    s.floor_max_m = {5.5, 3.0};
    const double x = 5.0, y = 2.5;
    s.walls = {{{-x, -y}, {x, -y}}, {{x, -y}, {x, y}}, {{x, y}, {-x, y}}, {{-x, y}, {-x, -y}}};
    sim::SceneObject table;
    table.id = 1;
    table.cls = ObjectClass::kTable;
    table.style = "rect_table";
    table.pose = {0.0, 0.3, 0.0};
    sim::SceneObject chair;
    chair.id = 2;
    chair.cls = ObjectClass::kChair;
    chair.style = "four_leg_chair";
    chair.table_id = 1;
    chair.pose = {0.0, -0.55, kPi / 2};  // facing the table
    s.objects = {table, chair};
    s.start = {-4.0, -1.0, 0.0};
    s.waypoint = {-1.5, -1.6, 0.0};
    s.goal = {4.0, -1.0, 0.0};
    return s;
}

NavParams fast_params() {
    NavParams p;
    p.lidar.azimuth_step_deg = 1.0;  // coarse sensor: keeps the test fast
    p.time_limit_s = 60.0;
    return p;
}

TEST(Navigation, EveryMethodReachesTheGoalWithoutCollisions) {
    const sim::Scene scene = corridor_with_table();
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    for (const std::string& name : nav_method_names()) {
        const NavMethod method = *nav_method(name);
        NoObjects none;
        GroundTruthObjects truth(scene, models, fast_params().system.navigator.monitor.body);
        ObjectSource& source = method.affordance ? static_cast<ObjectSource&>(truth) : none;
        const NavRunResult r = run_navigation(scene, method, source, fast_params());
        EXPECT_TRUE(r.success) << name << ": " << r.failure;
        EXPECT_EQ(r.collisions, 0) << name;
        EXPECT_GT(r.min_clearance_m, 0.0) << name;
        EXPECT_GT(r.distance_m,
                  r.shortest_m - fast_params().system.navigator.goal_tolerance_m - 0.05)
            << name;  // stops within tolerance
        EXPECT_LT(r.stop_distance_m, fast_params().system.navigator.goal_tolerance_m)
            << name;  // truth-fed: stops for real
        EXPECT_LT(r.time_s, 40.0) << name;
        EXPECT_GT(r.spl, 0.5) << name;
        EXPECT_LE(r.spl, 1.0) << name;
        EXPECT_FALSE(r.cycle_ms.empty());
    }
}

// Contacts built by hand: who moved toward whom at the moment of contact.
TEST(Navigation, ContactsAreTheRobotsWhenItMovesTowardWhatItTouches) {
    const double L = 0.508, W = 0.430;
    const Pose2 pose{2.0, 1.0, kPi / 2};  // facing +y
    const Eigen::Vector2d ahead(2.0, 1.25), left(1.8, 1.1), behind(2.0, 0.75);
    EXPECT_TRUE(robot_caused_contact(pose, 0.5, 0.0, ahead, L, W));    // drives into it
    EXPECT_FALSE(robot_caused_contact(pose, 0.0, 0.0, ahead, L, W));   // stopped: walked into
    EXPECT_FALSE(robot_caused_contact(pose, -0.3, 0.0, ahead, L, W));  // backing away from it
    EXPECT_TRUE(robot_caused_contact(pose, -0.3, 0.0, behind, L, W));  // backing into it
    EXPECT_FALSE(robot_caused_contact(pose, 0.5, 0.0, left, L,
                                      W));  // passing alongside: it came in from the side
    EXPECT_FALSE(robot_caused_contact(pose, 0.04, 0.0, ahead, L, W));  // creeping, below 0.05 m/s
    // Turning on the spot swings the front into what is on its left front (robot frame (0.2,
    // 0.21)).
    const Eigen::Vector2d left_front = to_isometry(pose) * Eigen::Vector2d(0.2, 0.21);
    EXPECT_TRUE(robot_caused_contact(pose, 0.0, 1.0, left_front, L, W));
    EXPECT_FALSE(robot_caused_contact(pose, 0.0, -1.0, left_front, L, W));
}

TEST(Navigation, MethodsDifferOnlyInInflationAndObjects) {
    const sim::RobotParams robot;
    EXPECT_NEAR(nav_method("con", robot)->inflation_radius_m, 3 * robot.circumscribed_radius_m(),
                1e-12);
    EXPECT_NEAR(nav_method("oppo", robot)->inflation_radius_m, robot.circumscribed_radius_m(),
                1e-12);
    EXPECT_TRUE(nav_method("gt-perc", robot)->affordance);
    EXPECT_FALSE(nav_method("con", robot)->affordance);
    // ours: gt-perc's planner and zones, objects from the perception chain.
    EXPECT_TRUE(nav_method("ours", robot)->affordance);
    EXPECT_NEAR(nav_method("ours", robot)->inflation_radius_m,
                nav_method("gt-perc", robot)->inflation_radius_m, 1e-12);
    EXPECT_TRUE(
        nav_method("ours", robot)->online);  // the only method on its own pose and perception
    EXPECT_FALSE(nav_method("gt-perc", robot)->online);
    EXPECT_FALSE(nav_method("fast").has_value());
}

TEST(Navigation, GroundTruthSourceFollowsPushedChairs) {
    sim::Scene s = corridor_with_table();
    s.pushers.push_back({2, 4.0, 0.4, 0.0});
    const std::vector<sim::ObjectModel> models = sim::models_of(s);
    const auto at0 = ground_truth_objects(s, models, 0.0);
    const auto at2 = ground_truth_objects(s, models, 2.0);  // fully pulled out
    EXPECT_NEAR(at2[1].box_world.centre_m.y() - at0[1].box_world.centre_m.y(), -0.4, 1e-9);
    EXPECT_EQ(at2[0].box_world.centre_m, at0[0].box_world.centre_m);
}

// gt-perc's objects carry what ours has from its CAD fits: each model's parts the body can hit,
// where the object stands now. Brute force: every surface point of a model in the body's band,
// placed at the object's pose, lies in one of the object's parts.
TEST(Navigation, GroundTruthSourceCarriesThePartsTheBodyCanHit) {
    sim::Scene s = corridor_with_table();
    s.objects[1].style = "office_chair";  // its star base: below the LiDAR's lowest beam up close
    s.pushers.push_back({2, 4.0, 0.4, 0.0});
    const std::vector<sim::ObjectModel> models = sim::models_of(s);
    const BodyHeights body;
    GroundTruthObjects plain(s, models);
    for (const ObjectEstimate& o : plain.objects({2.0})) EXPECT_TRUE(o.parts_world.empty());

    GroundTruthObjects truth(s, models, body);
    std::vector<Polygon2> chair_at0;
    for (const double t : {0.0, 2.0}) {
        const std::vector<ObjectEstimate> objects = truth.objects({t});
        const std::vector<sim::ObjectState> states = sim::object_states_at(s, models, t);
        ASSERT_EQ(objects.size(), 2u);
        EXPECT_EQ(objects[0].parts_world.size(), 4u) << "the table's legs (its top is above)";
        ASSERT_FALSE(objects[1].parts_world.empty());
        for (std::size_t i = 0; i < objects.size(); ++i) {
            int outside = 0, n = 0;
            for (const Eigen::Vector2d& q :
                 sim::low_surface_points(models[i].mesh_object, body, 0.02)) {
                const Eigen::Vector2d p =
                    (states[i].T_world_object * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>();
                double nearest = std::numeric_limits<double>::infinity();
                for (const Polygon2& part : objects[i].parts_world)
                    nearest = std::min(nearest, convex_distance(part, p));
                outside += nearest > 1e-6;
                ++n;
            }
            EXPECT_GT(n, 20) << i;
            EXPECT_EQ(outside, 0) << "object " << i << " at t = " << t;
        }
        if (t == 0.0) {
            chair_at0 = objects[1].parts_world;
            continue;
        }
        // Pulled 0.4 m straight back (-y): its parts with it, not where it stood.
        ASSERT_EQ(objects[1].parts_world.size(), chair_at0.size());
        for (std::size_t k = 0; k < chair_at0.size(); ++k) {
            ASSERT_EQ(objects[1].parts_world[k].size(), chair_at0[k].size());
            for (std::size_t v = 0; v < chair_at0[k].size(); ++v) {
                EXPECT_NEAR(objects[1].parts_world[k][v].x(), chair_at0[k][v].x(), 1e-9);
                EXPECT_NEAR(objects[1].parts_world[k][v].y(), chair_at0[k][v].y() - 0.4, 1e-9);
            }
        }
    }
}

}  // namespace
}  // namespace makeway::eval
