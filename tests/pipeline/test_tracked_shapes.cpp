#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../sim/sim_test_util.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/pipeline/tracked_shapes.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/lidar.hpp"

namespace makeway::pipeline {
namespace {

using verification::ShapePrior;

// One office chair in a room, scanned from two sides; the floor and ceiling cut by height.
struct Room {
    sim::SceneObject chair;
    sim::ObjectModel model;
    sim::Scene scene;
};

Room chair_room() {
    Room r;
    r.scene = sim::testing_util::box_room(5.0);
    r.chair.id = 3;
    r.chair.cls = ObjectClass::kChair;
    r.chair.style = std::string(sim::to_string(sim::FurnitureStyle::kOfficeChair));
    r.chair.model_seed = 9;
    r.chair.pose = {1.0, 0.6, 0.4};
    r.scene.objects.push_back(r.chair);
    r.model = sim::model_of(r.chair);
    return r;
}

PointCloud scan(const Room& room, const Isometry3& T_world_sensor, std::uint64_t seed) {
    sim::World world(room.scene, {room.model});
    PointCloud raw;
    for (int k = 0; k < 5; ++k)
        raw.append(sim::simulate_sweep(
            world, {}, [&](double) { return T_world_sensor; }, 0.1 * k, seed, k));
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const double h = (T_world_sensor * raw.xyz[i].cast<double>()).z();
        if (h > 0.08 && h < 2.2) keep.push_back(i);
    }
    return raw.select(keep);
}

// A stand-in for the learned prior: a given answer per keyframe; complete() records the views it
// was given and answers with the true mesh.
class RecordingPrior : public ShapePrior {
  public:
    std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>&, ObjectClass,
                                     double) const override {
        ++estimates;
        return answer;
    }
    std::optional<TriangleMesh> complete(const std::vector<View>& views, ObjectClass, double scale,
                                         const Eigen::Vector3d& offset_m) const override {
        ++completions;
        last_views = views;
        last_scale = scale;
        last_offset = offset_m;
        return mesh;
    }
    std::optional<Estimate> answer;
    TriangleMesh mesh;
    mutable int estimates = 0, completions = 0;
    mutable std::vector<View> last_views;
    mutable double last_scale = 0.0;
    mutable Eigen::Vector3d last_offset = Eigen::Vector3d::Zero();
};

// Share of a view's points within `tol` of the mesh.
double share_on_mesh(const ShapePrior::View& v, const TriangleMesh& mesh, double tol) {
    std::size_t on = 0;
    for (const auto& p : v.points_object) on += sim::testing_util::mesh_distance(mesh, p) < tol;
    return v.points_object.empty()
               ? 0.0
               : static_cast<double>(on) / static_cast<double>(v.points_object.size());
}

TEST(TrackedShapes, AnObjectsViewsAreFusedInItsFrameAndItsShapeServesLaterKeyframes) {
    const Room room = chair_room();
    const Isometry3 T_world_chair = lift_to_3d(room.chair.pose);
    RecordingPrior prior;
    prior.mesh = room.model.mesh_object;
    TrackedShapes shapes(&prior);
    const verification::CadLibrary none;
    const double floor_z = -0.45;

    // Keyframe 1, from the west: the prior's answer is 20 deg and 10 cm off; ICP against its mesh
    // finds the truth; the track gains its first view (no completion from one view: the prior's
    // mesh was made from it).
    const Isometry3 T_world_a = make_T_xyz_yaw({-1.5, 0.0, 0.45}, 0.0);
    const PointCloud cloud_a = scan(room, T_world_a, 1);
    Detection det;
    det.cls = ObjectClass::kChair;
    det.box_sensor = room.model.box_object.transformed(T_world_a.inverse() * T_world_chair);
    ShapePrior::Estimate e;
    e.mesh_object = room.model.mesh_object;
    e.T_sensor_object = T_world_a.inverse() *
                        make_T_xyz_yaw(T_world_chair.translation() + Eigen::Vector3d(0.1, -0.05, 0),
                                       0.4 + deg_to_rad(20));
    e.scale = 0.8;
    e.offset_m = Eigen::Vector3d(0, 0, -0.02);
    prior.answer = e;
    shapes.begin_keyframe(T_world_a);
    const auto v1 = verification::verify_detections(
        cloud_a, {det}, none, {}, [&](double, double) { return floor_z; }, &shapes);
    ASSERT_TRUE(v1[0].accepted) << v1[0].reason;
    ASSERT_TRUE(v1[0].shape.has_value());
    EXPECT_EQ(prior.estimates, 1);
    EXPECT_EQ(shapes.add_views(cloud_a, v1, {7}, {7}), 0u);
    ASSERT_EQ(shapes.shapes().count(7), 1u);
    const TrackedShapes::Shape& s = shapes.shapes().at(7);
    ASSERT_EQ(s.views.size(), 1u);
    EXPECT_GT(s.views[0].points_object.size(), 100u);
    EXPECT_GT(share_on_mesh(s.views[0], room.model.mesh_object, 0.05), 0.9);
    EXPECT_LT((s.T_world_object.translation() - T_world_chair.translation()).norm(), 0.03);
    EXPECT_LT(std::abs(rad_to_deg(angle_diff(yaw_of(s.T_world_object), 0.4))), 3.0);
    EXPECT_DOUBLE_EQ(s.scale, 0.8);
    EXPECT_LT((s.centre_object - room.model.box_object.centre_m).norm(),
              1e-6);  // where estimate() looks

    // Keyframe 2, from the south: the segment stands where the track's shape is, so that shape
    // is verified (the prior is not asked again), and the second view lands on the same mesh in
    // the same object frame; the shape is completed from both, through the first estimate's frame.
    const Isometry3 T_world_b = make_T_xyz_yaw({1.2, -2.0, 0.45}, kPi / 2);
    const PointCloud cloud_b = scan(room, T_world_b, 2);
    det.box_sensor = room.model.box_object.transformed(T_world_b.inverse() * T_world_chair);
    prior.answer.reset();
    shapes.begin_keyframe(T_world_b);
    const auto v2 = verification::verify_detections(
        cloud_b, {det}, none, {}, [&](double, double) { return floor_z; }, &shapes);
    ASSERT_TRUE(v2[0].accepted) << v2[0].reason;
    EXPECT_EQ(prior.estimates, 1);
    EXPECT_EQ(shapes.add_views(cloud_b, v2, {7}, {7}), 1u);
    EXPECT_EQ(prior.completions, 1);
    ASSERT_EQ(prior.last_views.size(), 2u);
    EXPECT_DOUBLE_EQ(prior.last_scale, 0.8);
    EXPECT_DOUBLE_EQ(prior.last_offset.z(), -0.02);
    for (const auto& view : prior.last_views)
        EXPECT_GT(share_on_mesh(view, room.model.mesh_object, 0.05), 0.9);
    const Eigen::Vector3d origin_b = T_world_chair.inverse() * T_world_b.translation();
    EXPECT_LT((prior.last_views[1].origin_object - origin_b).norm(), 0.05);
    EXPECT_EQ(shapes.shapes().at(7).completions, 1u);

    // Another class, or a segment farther than match_distance_m from every shape: the prior.
    shapes.begin_keyframe(T_world_b);
    shapes.estimate(verification::segment_points(cloud_b, det.box_sensor, 0.1), ObjectClass::kTable,
                    floor_z);
    EXPECT_EQ(prior.estimates, 2);
    shapes.begin_keyframe(
        make_T_xyz_yaw({1.2, -1.5, 0.45}, kPi / 2));  // the same points, 0.5 m away in the world
    shapes.estimate(verification::segment_points(cloud_b, det.box_sensor, 0.1), ObjectClass::kChair,
                    floor_z);
    EXPECT_EQ(prior.estimates, 3);

    // The track leaves the map: its shape goes with it.
    shapes.add_views(cloud_b, {}, {}, {});
    EXPECT_TRUE(shapes.shapes().empty());
}

TEST(TrackedShapes, RefusesBadParametersAndNoPrior) {
    RecordingPrior prior;
    EXPECT_THROW(TrackedShapes(nullptr), std::invalid_argument);
    EXPECT_THROW(TrackedShapes(&prior, TrackedShapeParams{.match_distance_m = 0.0}),
                 std::invalid_argument);
    EXPECT_THROW(TrackedShapes(&prior, TrackedShapeParams{.max_views = 0}), std::invalid_argument);
    EXPECT_NO_THROW(TrackedShapes(&prior, TrackedShapeParams{}));
}

}  // namespace
}  // namespace makeway::pipeline
