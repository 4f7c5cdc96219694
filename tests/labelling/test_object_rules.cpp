// Step 5 of the annotation rule by rule, on clusters built in the test from a chair's CAD model
// (its surface at a known pose, seeded noise): each rule accepts the chair and refuses it when the
// one thing that rule judges is wrong.
#include <gtest/gtest.h>

#include "makeway/common/random.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/labelling/object_rules.hpp"
#include "makeway/labelling/upright_box.hpp"
#include "makeway/sim/furniture.hpp"

namespace makeway::labelling {
namespace {

struct ChairCluster {
    std::vector<verification::CadLibrary> one_model;
    Cluster cluster;
    OrientedBox box_world;  ///< the chair's own points' box (the far points stay outside it)
    Isometry3 T_world_object;
    std::size_t chair_points = 0;
};

// A four-leg chair's sampled surface at (2, 1) turned by 0.3 rad, `noise_m` Gaussian noise per
// axis, plus `far` points 2 m away (another object the cluster swallowed; outside the chair's box).
ChairCluster chair_cluster(double noise_m, std::size_t far = 0, std::uint64_t seed = 3) {
    ChairCluster c;
    verification::CadLibrary library;
    library.add("chair", ObjectClass::kChair,
                sim::make_furniture(sim::FurnitureStyle::kFourLegChair, 4).mesh_object);
    c.one_model.push_back(library.only(0));
    c.T_world_object = make_T_xyz_yaw({2.0, 1.0, 0.0}, 0.3);
    Rng rng = make_rng(seed);
    for (const Eigen::Vector3d& p :
         c.one_model.front().models().front().levels.back().points_object) {
        c.cluster.points_world.push_back(
            c.T_world_object * p + Eigen::Vector3d(normal(rng, 0, noise_m), normal(rng, 0, noise_m),
                                                   normal(rng, 0, noise_m)));
    }
    c.chair_points = c.cluster.points_world.size();
    c.box_world = upright_pca_box(c.cluster.points_world, 0.0);
    for (std::size_t i = 0; i < far; ++i) {
        c.cluster.points_world.emplace_back(4.0 + uniform(rng, 0, 0.3), 1.0 + uniform(rng, 0, 0.3),
                                            uniform(rng, 0.1, 0.6));
    }
    c.cluster.movable.assign(c.cluster.points_world.size(), 1);
    return c;
}

LabelParams params() { return LabelParams{}; }

TEST(ObjectRules, TheResidualRuleTakesAScanOfTheChairAndRefusesANoisyOne) {
    const ChairCluster c = chair_cluster(0.003);
    ASSERT_GT(c.chair_points, 200u);
    const auto fit = fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, {}, params());
    ASSERT_TRUE(fit.has_value());
    EXPECT_LT(fit->verified.residual_m, params().verify.e_max_m);
    EXPECT_EQ(fit->explained, c.chair_points);
    EXPECT_LT((fit->verified.T_sensor_object.translation() - c.T_world_object.translation())
                  .head<2>()
                  .norm(),
              0.03);
    // 5 cm of noise per axis: no model fits within the labeller's e_max (2.5 cm).
    const ChairCluster noisy = chair_cluster(0.05);
    EXPECT_FALSE(fit_cad_model(noisy.cluster, noisy.box_world, 0.0, noisy.one_model, {}, params())
                     .has_value());
}

TEST(ObjectRules, TheExplainedShareRuleRefusesAModelThatExplainsTooLittle) {
    // The chair's points and as many again 2 m away: the fit explains half the cluster.
    ChairCluster c = chair_cluster(0.003, 0);
    c = chair_cluster(0.003, c.chair_points);
    const double share =
        static_cast<double>(c.chair_points) / static_cast<double>(c.cluster.points_world.size());
    LabelParams p = params();
    p.min_coverage = share - 0.05;
    const auto fit = fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, {}, p);
    ASSERT_TRUE(fit.has_value());
    EXPECT_EQ(fit->explained, c.chair_points);
    p.min_coverage = share + 0.05;
    EXPECT_FALSE(fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, {}, p).has_value());
    p = params();
    p.min_object_points = c.chair_points + 1;  // the other half of the rule: enough points at all
    EXPECT_FALSE(fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, {}, p).has_value());
}

TEST(ObjectRules, TheFreeSpaceRuleRefusesAModelTheSessionSawThrough) {
    const ChairCluster c = chair_cluster(0.003);
    Isometry3 seen_at = Isometry3::Identity();
    const SeenThrough mostly_free = [&](const verification::CadModel&, const Isometry3& T) {
        seen_at = T;
        return params().max_seen_through + 0.1;
    };
    EXPECT_FALSE(
        fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, mostly_free, params()).has_value());
    EXPECT_LT((seen_at.translation() - c.T_world_object.translation()).head<2>().norm(),
              0.03);  // asked at the fit's pose
    const SeenThrough mostly_hit = [](const verification::CadModel&, const Isometry3&) {
        return 0.1;
    };
    const auto fit = fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, mostly_hit, params());
    ASSERT_TRUE(fit.has_value());
    EXPECT_EQ(fit->seen_through, 0.1);
}

TEST(ObjectRules, WhatAFitLeavesFarFromItsModelIsClusteredAgain) {
    // The chair and, 2 m away, half as many points again: a third of the cluster is not the
    // chair's.
    const std::size_t far = chair_cluster(0.003).chair_points / 2;
    const ChairCluster c = chair_cluster(0.003, far);
    LabelParams p = params();
    p.min_coverage = 0.5;
    const auto fit = fit_cad_model(c.cluster, c.box_world, 0.0, c.one_model, {}, p);
    ASSERT_TRUE(fit.has_value());
    const auto rest = unexplained_rest(c.cluster, *fit, p);
    ASSERT_TRUE(rest.has_value());
    EXPECT_EQ(rest->points_world.size(), far);  // the far points, none of the chair's
    EXPECT_EQ(rest->depth, 1);
    for (const Eigen::Vector3d& q : rest->points_world) EXPECT_GT(q.x(), 3.9);
    // Too small a share of the cluster, or split too often already: the rest is the object's noise.
    p.split_share = 0.4;
    EXPECT_FALSE(unexplained_rest(c.cluster, *fit, p).has_value());
    p = params();
    Cluster deep = c.cluster;
    deep.depth = p.max_splits;
    EXPECT_FALSE(unexplained_rest(deep, *fit, p).has_value());
}

TEST(ObjectRules, FurnitureSizeMovablePartsAndClusters) {
    const LabelParams p = params();
    OrientedBox box{Eigen::Vector3d(0, 0, 0.4), Eigen::Vector3d(0.5, 0.5, 0.8), 0.0};
    EXPECT_TRUE(furniture_sized(box, 0.0, p));
    box.size_m.z() = 2.4;  // 2 m above the floor: a wall, a pillar
    box.centre_m.z() = 1.2;
    EXPECT_FALSE(furniture_sized(box, 0.0, p));
    box = {Eigen::Vector3d(0, 0, 0.4), Eigen::Vector3d(3.5, 0.5, 0.8), 0.0};
    EXPECT_FALSE(furniture_sized(box, 0.0, p));
    // A wall with a chair against it: the chair's Movable points go on; all Movable, or split too
    // often: nothing.
    Cluster wall;
    for (int i = 0; i < 100; ++i) {
        wall.points_world.emplace_back(0.02 * i, 0.0, 1.0);
        wall.movable.push_back(i < 30);
    }
    const auto part = movable_part(wall, p);
    ASSERT_TRUE(part.has_value());
    EXPECT_EQ(part->size(), 30u);
    Cluster all = wall;
    all.movable.assign(100, 1);
    EXPECT_FALSE(movable_part(all, p).has_value());
    wall.depth = p.max_splits;
    EXPECT_FALSE(movable_part(wall, p).has_value());
    // Two blobs 1 m apart and one too small; stacked blobs 0.15 m apart join when heights count
    // less.
    std::vector<Eigen::Vector3d> pts;
    Rng rng = make_rng(8);
    const auto blob = [&](const Eigen::Vector3d& at, int n, double r) {
        for (int i = 0; i < n; ++i)
            pts.push_back(at + Eigen::Vector3d(uniform(rng, -r, r), uniform(rng, -r, r),
                                               uniform(rng, -r, r)));
    };
    blob({0, 0, 0.5}, 60, 0.1);
    blob({1, 0, 0.5}, 60, 0.1);
    blob({3, 0, 0.5}, 10, 0.1);
    EXPECT_EQ(cluster_points(pts, std::vector<char>(pts.size(), 0), 0, p).size(), 2u);
    pts.clear();
    blob({0, 0, 0.3}, 60, 0.05);
    blob({0, 0, 0.55}, 60, 0.05);  // 0.15 m gap between the two
    LabelParams flat = p;
    EXPECT_EQ(cluster_points(pts, std::vector<char>(pts.size(), 0), 0, flat).size(), 2u);
    flat.dbscan_z_scale = 0.4;
    const auto joined = cluster_points(pts, std::vector<char>(pts.size(), 0), 2, flat);
    ASSERT_EQ(joined.size(), 1u);
    EXPECT_EQ(joined.front().points_world.size(), 120u);
    EXPECT_EQ(joined.front().depth, 2);
}

// The residual bound a file sets (labelling.verify_e_max_m) is reported once, under its key; the
// verifier's own checks still speak for the members no file sets.
TEST(ObjectRules, ABadResidualBoundIsReportedOnce) {
    LabelParams p;
    EXPECT_TRUE(p.validate().empty());
    p.verify.e_max_m = -1.0;
    const std::vector<std::string> e = p.validate();
    ASSERT_EQ(e.size(), 1u) << ::testing::PrintToString(e);
    EXPECT_NE(e[0].find("labelling.verify_e_max_m"), std::string::npos) << e[0];
    p = LabelParams();
    p.verify.max_models = 0;  // not a key of the file: the verifier's check
    const std::vector<std::string> v = p.validate();
    ASSERT_EQ(v.size(), 1u) << ::testing::PrintToString(v);
    EXPECT_EQ(v[0].rfind("labelling.verify: ", 0), 0u) << v[0];
}

}  // namespace
}  // namespace makeway::labelling
