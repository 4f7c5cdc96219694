// Placing other tools' meshes in the object frame: every up/forward pair, units, re-centring.
#include <gtest/gtest.h>

#include "makeway/common/mesh_placement.hpp"

namespace makeway {
namespace {

// A "chair" drawn by an author: seat 0.5 wide, 0.4 deep, 0.9 tall, with a marker vertex at its
// back, given in the author's axes (up, forward) and origin.
TriangleMesh authored(const Eigen::Vector3d& up, const Eigen::Vector3d& forward,
                      const Eigen::Vector3d& origin) {
    const Eigen::Vector3d side = up.cross(forward);
    TriangleMesh m;
    for (double f : {-0.2, 0.2}) {
        for (double s : {-0.25, 0.25}) {
            for (double u : {0.0, 0.9})
                m.vertices_m.push_back((origin + f * forward + s * side + u * up).cast<float>());
        }
    }
    m.vertices_m.push_back(
        (origin - 0.2 * forward + 0.8 * up).cast<float>());  // the back rest's top
    m.triangles = {{0, 1, 2}, {2, 3, 4}, {5, 6, 7}, {7, 8, 0}};
    return m;
}

TEST(MeshPlacement, EveryUpAndForwardPairTurnsTheChairUprightFacingX) {
    const MeshAxis axes[] = {MeshAxis::kPosX, MeshAxis::kNegX, MeshAxis::kPosY,
                             MeshAxis::kNegY, MeshAxis::kPosZ, MeshAxis::kNegZ};
    int pairs = 0;
    for (MeshAxis up : axes) {
        for (MeshAxis fwd : axes) {
            const auto R = placement_rotation(up, fwd);
            if (std::abs(axis_vector(up).dot(axis_vector(fwd))) > 0.5) {
                EXPECT_FALSE(R.has_value());
                EXPECT_THROW(place_mesh(authored(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                                 Eigen::Vector3d::Zero()),
                                        {up, fwd, 1.0, true}),
                             std::invalid_argument);
                continue;
            }
            ++pairs;
            ASSERT_TRUE(R.has_value());
            EXPECT_NEAR(R->determinant(), 1.0, 1e-12);  // a rotation, never a mirror
            const TriangleMesh m = place_mesh(
                authored(axis_vector(up), axis_vector(fwd), {3, -2, 7}), {up, fwd, 1.0, true});
            Eigen::Vector3f lo = m.vertices_m[0], hi = lo;
            for (const auto& v : m.vertices_m) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
            EXPECT_NEAR(hi.z() - lo.z(), 0.9, 1e-5);  // upright
            EXPECT_NEAR(lo.z(), 0.0, 1e-5);           // on the floor
            EXPECT_NEAR(hi.x() - lo.x(), 0.4, 1e-5);  // depth along x
            EXPECT_NEAR(lo.x() + hi.x(), 0.0, 1e-5);  // footprint centred
            EXPECT_NEAR(lo.y() + hi.y(), 0.0, 1e-5);
            EXPECT_NEAR(m.vertices_m.back().x(), -0.2,
                        1e-5);  // the back rest behind: the chair faces +x
            EXPECT_NEAR(m.vertices_m.back().z(), 0.8, 1e-5);
        }
    }
    EXPECT_EQ(pairs, 24);
}

TEST(MeshPlacement, UnitsScaleAndPlausibility) {
    EXPECT_DOUBLE_EQ(*parse_length_unit("cm"), 0.01);
    EXPECT_DOUBLE_EQ(*parse_length_unit("in"), 0.0254);
    EXPECT_FALSE(parse_length_unit("furlong"));
    EXPECT_EQ(*parse_mesh_axis("-Y"), MeshAxis::kNegY);
    EXPECT_EQ(*parse_mesh_axis("z"), MeshAxis::kPosZ);
    EXPECT_FALSE(parse_mesh_axis("w"));
    // Drawn in centimetres: 90 units tall is 0.9 m; read as metres it is 90 m, and said to be
    // wrong.
    TriangleMesh cm =
        authored(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero());
    for (auto& v : cm.vertices_m) v *= 100.0f;
    EXPECT_FALSE(implausible_furniture_extent(
        place_mesh(cm, {MeshAxis::kPosZ, MeshAxis::kPosX, 0.01, true}), ObjectClass::kChair));
    const auto warning = implausible_furniture_extent(place_mesh(cm, {}), ObjectClass::kChair);
    ASSERT_TRUE(warning.has_value());
    EXPECT_NE(warning->find("wrong units or up axis"), std::string::npos) << *warning;
    // The same for a table.
    EXPECT_TRUE(implausible_furniture_extent(
        place_mesh(cm, {MeshAxis::kPosZ, MeshAxis::kPosX, 1.0, false}), ObjectClass::kTable));
    // Without re-centring the author's origin stays.
    const TriangleMesh kept =
        place_mesh(authored(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), {1, 1, 1}),
                   {MeshAxis::kPosZ, MeshAxis::kPosX, 1.0, false});
    EXPECT_NEAR(kept.vertices_m[0].z(), 1.0, 1e-6);
}

}  // namespace
}  // namespace makeway
