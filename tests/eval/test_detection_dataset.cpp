#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "makeway/eval/detection_dataset.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
namespace {

std::vector<std::string> names_of(const std::vector<UserFurniture>& v) {
    std::vector<std::string> out;
    for (const UserFurniture& f : v) out.push_back(f.name);
    return out;
}

// Every third model of each class, by name, is held out: the same split whatever the folder's
// order, the two parts disjoint and together everything.
TEST(DetectionDataset, RealModelsAreSplitByNameWithinEachClass) {
    std::vector<UserFurniture> all;
    for (const char* n : {"c0", "c1", "c2", "c3", "c4", "c5", "c6"})
        all.push_back({n, ObjectClass::kChair, nullptr});
    for (const char* n : {"t0", "t1", "t2", "t3"}) all.push_back({n, ObjectClass::kTable, nullptr});
    std::vector<UserFurniture> shuffled = all;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
    const FurnitureSplit a = split_furniture(all, 3), b = split_furniture(shuffled, 3);
    EXPECT_EQ(names_of(a.held_out), (std::vector<std::string>{"c2", "c5", "t2"}));
    EXPECT_EQ(names_of(a.train),
              (std::vector<std::string>{"c0", "c1", "c3", "c4", "c6", "t0", "t1", "t3"}));
    EXPECT_EQ(names_of(b.held_out), names_of(a.held_out));
    EXPECT_EQ(names_of(b.train), names_of(a.train));
    EXPECT_TRUE(split_furniture(all, 0).held_out.empty());
    EXPECT_EQ(split_furniture(all, 0).train.size(), all.size());
}

// Clutter is seen by the LiDAR and labelled as nothing: rooms of clutter alone give keyframes
// without a single label whose points lie on the clutter.
TEST(DetectionDataset, ClutterIsSeenAndNeverLabelled) {
    DatasetParams p;
    p.scenes = 1;
    p.seed = 21;
    p.max_keyframes_per_scene = 3;
    p.keyframe_every = 5;  // 15 sweeps: small enough for the sanitizer job
    p.clutter.count = 8;
    p.clutter_only = true;
    std::vector<sim::Scene> scenes;
    const std::vector<LabelledKeyframe> kfs = generate_detection_dataset(p, {}, &scenes);
    ASSERT_EQ(kfs.size(), 3u);
    ASSERT_EQ(scenes.size(), 1u);
    EXPECT_TRUE(scenes[0].objects.empty());
    ASSERT_GE(scenes[0].environment.size(), 4u);
    std::size_t on_clutter = 0;
    for (const LabelledKeyframe& kf : kfs) {
        EXPECT_TRUE(kf.objects.empty());
        EXPECT_TRUE(kf.unseen.empty());
        for (const Eigen::Vector3f& q : kf.cloud_sensor.xyz) {
            const Eigen::Vector3d w = kf.T_world_sensor * q.cast<double>();
            for (const sim::EnvironmentMesh& e : scenes[0].environment) {
                Eigen::Vector3d lo, hi;
                mesh_bounds(*e.mesh_world, lo, hi);
                if ((w.head<2>().array() >= lo.head<2>().array() - 0.1).all() &&
                    (w.head<2>().array() <= hi.head<2>().array() + 0.1).all()) {
                    ++on_clutter;
                    break;
                }
            }
        }
    }
    EXPECT_GT(on_clutter, 500u);
}

// The command line's names of the fits: each parses back to its fit, and nothing else parses.
TEST(SceneCad, FitNamesRoundTrip) {
    ASSERT_EQ(cad_fits_by_name().size(), 3u);
    for (const auto& [name, fit] : cad_fits_by_name()) {
        EXPECT_EQ(to_string(fit), name);
        EXPECT_EQ(parse_cad_fit(name), fit);
    }
    EXPECT_EQ(parse_cad_fit("other_dimensions"), std::nullopt);
    EXPECT_EQ(parse_cad_fit(""), std::nullopt);
}

// Approximate CAD libraries (issue 32): the same models in the same order, each scaled by
// 0.9-1.1 per axis, or its style at other dimensions; the same scene gives the same library.
TEST(SceneCad, ApproximateLibrariesAreCloseButNotTheModels) {
    const sim::Scene scene = sim::generate_scene({.seed = 2, .density = sim::Density::kMedium});
    const verification::CadLibrary exact = scene_cad_library(scene);
    const verification::CadLibrary scaled = scene_cad_library(scene, CadFit::kScaled);
    const verification::CadLibrary other = scene_cad_library(scene, CadFit::kOtherDimensions);
    ASSERT_GT(exact.models().size(), 3u);
    ASSERT_EQ(scaled.models().size(), exact.models().size());
    ASSERT_EQ(other.models().size(), exact.models().size());
    std::size_t other_differs = 0;
    for (std::size_t i = 0; i < exact.models().size(); ++i) {
        const Eigen::Vector3d e = exact.models()[i].box_object.size_m;
        const Eigen::Vector3d s = scaled.models()[i].box_object.size_m;
        EXPECT_EQ(scaled.models()[i].cls, exact.models()[i].cls);
        EXPECT_FALSE(s.isApprox(e, 1e-6)) << exact.models()[i].name;
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(s(a), 0.9 * e(a) - 1e-6);
            EXPECT_LE(s(a), 1.1 * e(a) + 1e-6);
        }
        if (!other.models()[i].box_object.size_m.isApprox(e, 1e-3)) ++other_differs;
    }
    EXPECT_GE(other_differs, exact.models().size() - 1);
    const verification::CadLibrary again = scene_cad_library(scene, CadFit::kScaled);
    EXPECT_TRUE(again.models()[0].box_object.size_m.isApprox(scaled.models()[0].box_object.size_m));
}

}  // namespace
}  // namespace makeway::eval
