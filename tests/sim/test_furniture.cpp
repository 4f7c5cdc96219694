#include <gtest/gtest.h>

#include "makeway/common/mesh_placement.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::sim {
namespace {

TEST(Furniture, EveryStyleIsAValidModelOfRealSize) {
    for (int i = 0; i < kNumFurnitureStyles; ++i) {
        const auto style = static_cast<FurnitureStyle>(i);
        EXPECT_EQ(parse_furniture_style(to_string(style)), style);
        for (std::uint64_t seed = 0; seed < 20; ++seed) {
            const FurnitureModel m = make_furniture(style, seed);
            ASSERT_EQ(m.mesh_object.validity_error(), "") << to_string(style);
            ASSERT_GT(m.mesh_object.num_triangles(), 11u);
            const Eigen::Vector3d size = m.box_object.size_m;
            Eigen::Vector3d lo, hi;
            mesh_bounds(m.mesh_object, lo, hi);
            EXPECT_NEAR(lo.z(), 0.0, 1e-6);           // stands on the floor
            EXPECT_NEAR(lo.x() + hi.x(), 0.0, 1e-5);  // footprint centred
            EXPECT_NEAR(lo.y() + hi.y(), 0.0, 1e-5);
            EXPECT_TRUE(((hi - lo) - size).cwiseAbs().maxCoeff() < 1e-5);
            // Every style is a plausible piece of furniture of its class (the check user meshes
            // get).
            TriangleMesh placed = m.mesh_object;
            EXPECT_FALSE(implausible_furniture_extent(placed, class_of(style)).has_value())
                << to_string(style);
            if (static_cast<int>(style) > static_cast<int>(FurnitureStyle::kConferenceTable))
                continue;  // the wider world
            if (class_of(style) == ObjectClass::kChair) {
                EXPECT_GT(size.z(), 0.44) << to_string(style);
                EXPECT_LT(size.z(), 1.3) << to_string(style);
                EXPECT_LT(size.head<2>().maxCoeff(), 0.95) << to_string(style);
            } else {
                EXPECT_NEAR(size.z(), 0.74, 0.021) << to_string(style);
                EXPECT_GT(size.head<2>().maxCoeff(), 0.79) << to_string(style);
                EXPECT_LT(size.head<2>().maxCoeff(), 3.61) << to_string(style);
            }
        }
    }
}

TEST(Furniture, SeedNamesOneModel) {
    const FurnitureModel a = make_furniture(FurnitureStyle::kOfficeChair, 5);
    const FurnitureModel b = make_furniture(FurnitureStyle::kOfficeChair, 5);
    const FurnitureModel c = make_furniture(FurnitureStyle::kOfficeChair, 6);
    EXPECT_EQ(a.mesh_object.vertices_m, b.mesh_object.vertices_m);
    EXPECT_NE(a.mesh_object.vertices_m, c.mesh_object.vertices_m);
}

TEST(Furniture, ChairsHaveTheirBackAtMinusX) {
    // The backrest rises behind the seat: the highest vertices lie in the rear half.
    for (auto style :
         {FurnitureStyle::kFourLegChair, FurnitureStyle::kOfficeChair, FurnitureStyle::kArmchair,
          FurnitureStyle::kStackingChair, FurnitureStyle::kSledChair,
          FurnitureStyle::kCantileverChair, FurnitureStyle::kSofa, FurnitureStyle::kLoungeChair,
          FurnitureStyle::kFoldingChair}) {
        const FurnitureModel m = make_furniture(style, 1);
        const double top = m.box_object.size_m.z();
        for (const auto& v : m.mesh_object.vertices_m) {
            if (v.z() > top - 0.02) {
                EXPECT_LT(v.x(), 0.0f) << to_string(style);
            }
        }
    }
    EXPECT_EQ(styles_of(ObjectClass::kChair).size(), 12u);
    EXPECT_EQ(styles_of(ObjectClass::kTable).size(), 9u);
    EXPECT_EQ(scene_styles_of(ObjectClass::kChair).size(), 4u);  // what generated scenes draw
    EXPECT_EQ(scene_styles_of(ObjectClass::kTable).size(), 3u);
}

TEST(Furniture, SledAndCantileverChairsRestOnLowRunners) {
    // Their runners are what a robot drives into: a part within 3 cm of the floor, 0.4 m long.
    for (auto style : {FurnitureStyle::kSledChair, FurnitureStyle::kCantileverChair}) {
        const FurnitureModel m = make_furniture(style, 3);
        float lo = 1e9f, hi = -1e9f;
        for (const auto& v : m.mesh_object.vertices_m) {
            if (v.z() < 0.03f) lo = std::min(lo, v.x()), hi = std::max(hi, v.x());
        }
        EXPECT_GT(hi - lo, 0.4f) << to_string(style);
    }
}

TEST(MeshPrimitives, ClosedBoxArea) {
    TriangleMesh m;
    add_box(m, {1, 2, 3}, {1, 2, 3}, 0.7);
    EXPECT_NEAR(surface_area_m2(m), 2 * (2 + 3 + 6), 1e-5);
    TriangleMesh cyl;
    add_cylinder(cyl, {0, 0, 0}, 1.0, 2.0, 256);
    EXPECT_NEAR(surface_area_m2(cyl), 2 * 3.14159265 + 4 * 3.14159265, 1e-3);
}

}  // namespace
}  // namespace makeway::sim
