#include <gtest/gtest.h>

#include "makeway/common/oriented_box.hpp"
#include "makeway/sim/clutter.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::sim {
namespace {

// Every kind is a thing of furniture size standing on the floor, centred on its origin: what the
// detector has to learn is not a chair or a table.
TEST(Clutter, EveryKindStandsOnTheFloorAtFurnitureSize) {
    Rng rng = make_rng(3);
    for (int k = 0; k < kClutterKinds; ++k) {
        for (int draw = 0; draw < 20; ++draw) {
            const TriangleMesh m = make_clutter(static_cast<ClutterKind>(k), rng);
            ASSERT_GT(m.num_triangles(), 0u) << to_string(static_cast<ClutterKind>(k));
            Eigen::Vector3d lo, hi;
            mesh_bounds(m, lo, hi);
            EXPECT_NEAR(lo.z(), 0.0, 1e-6) << to_string(static_cast<ClutterKind>(k));
            EXPECT_GT(hi.z(), 0.2);
            EXPECT_LT(hi.z(), 2.1);
            EXPECT_LT((hi - lo).head<2>().norm(), 2.6);
            EXPECT_LT((0.5 * (hi + lo)).head<2>().norm(), 0.1);  // centred
        }
    }
}

// Clutter goes on free floor: clear of every chair and table (their boxes at time 0), of the
// mission's poses; the same seed gives the same room.
TEST(Clutter, PlacedOnFreeFloorReproducibly) {
    const Scene base = generate_scene({.seed = 4, .density = Density::kMedium});
    Scene a = base, b = base;
    const ClutterParams params{.count = 8};
    const int placed = add_clutter(a, params, 11);
    ASSERT_EQ(add_clutter(b, params, 11), placed);
    EXPECT_GE(placed, 4);
    ASSERT_EQ(a.environment.size(), static_cast<std::size_t>(placed));
    std::vector<OrientedBox> boxes;
    for (const SceneObject& o : base.objects)
        boxes.push_back(model_of(o).box_object.transformed(lift_to_3d(o.pose)));
    for (std::size_t i = 0; i < a.environment.size(); ++i) {
        const TriangleMesh& m = *a.environment[i].mesh_world;
        EXPECT_EQ(m.vertices_m, b.environment[i].mesh_world->vertices_m);
        for (const Eigen::Vector3f& v : m.vertices_m) {
            const Eigen::Vector3d p = v.cast<double>();
            EXPECT_TRUE(a.on_floor(p.head<2>()));
            for (const OrientedBox& box : boxes) EXPECT_FALSE(box.contains(p, 0.2));
            for (const Pose2& q : {a.start, a.goal})
                EXPECT_GT((p.head<2>() - Eigen::Vector2d(q.x_m, q.y_m)).norm(), 1.0);
        }
    }
    EXPECT_EQ(a.validate(), std::vector<std::string>{});
}

}  // namespace
}  // namespace makeway::sim
