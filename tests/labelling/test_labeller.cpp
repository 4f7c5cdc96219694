// The annotation on two simulated sessions of one room: the objects it finds are the room's
// furniture, and it cannot see the simulator's labels (the same result with them scrambled).
#include <gtest/gtest.h>

#include <random>

#include "makeway/common/box_overlap.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/labelling/labeller.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::labelling {
namespace {

struct LabelRun {
    LabelResult result;
    std::vector<sim::Scene> scenes;
};

LabelRun label_two_sessions(bool scramble_labels, int frames_per_session) {
    sim::SceneGenParams g;
    g.seed = 11;
    g.density = sim::Density::kMedium;
    g.people = false;
    const sim::Scene base = sim::generate_scene(g);
    LabelParams p;
    p.system.T_base_sensor = sim::RobotParams{}.T_robot_sensor();
    Labeller labeller(p);
    LabelRun run;
    std::mt19937 rng(5);
    for (int s = 0; s < 2; ++s) {
        run.scenes.push_back(sim::make_session(base, s));
        const sim::Scene& scene = run.scenes.back();
        const sim::RobotParams robot;
        const sim::CollisionChecker checker(scene, sim::models_of(scene), robot);
        const auto route = sim::drive_route(scene, checker, robot);
        EXPECT_TRUE(route.has_value());
        if (!route) return run;
        sim::SequenceParams sp;
        sp.seed = 100 + static_cast<std::uint64_t>(s);
        sim::SequenceSimulator simulator(scene, *route, sp);
        labeller.begin_session(simulator.start_pose());
        for (int f = 0; f < frames_per_session && !simulator.reached_goal(); ++f) {
            sim::SimFrame frame = simulator.next();
            if (scramble_labels) {
                for (auto& l : frame.points_sensor.label)
                    l = static_cast<std::uint8_t>(rng() % kNumSemanticLabels);
                for (auto& i : frame.points_sensor.instance)
                    i = static_cast<std::uint32_t>(rng() % 50);
            }
            labeller.add_sweep({frame.points_sensor, frame.stamp_s, sp.lidar.sweep_duration_s(),
                                frame.odometry_pose, frame.odometry_end_pose});
        }
    }
    const verification::CadLibrary library = eval::scene_cad_library(base);
    run.result = labeller.finish(&library);
    return run;
}

TEST(Labeller, FindsTheRoomsFurnitureWithoutTheSimulatorsLabels) {
    const LabelRun run = label_two_sessions(false, 90);
    const LabelResult& r = run.result;
    ASSERT_EQ(r.sessions.size(), 2u);
    EXPECT_LT(r.reports[1].alignment.residual_m, 0.03);
    EXPECT_LT(r.reports[1].alignment.correction_m, 0.05);
    // Every CAD-fitted object is a piece of that session's furniture, of the right class.
    std::size_t fitted = 0, right = 0;
    for (const LabelledWorldObject& o : r.objects) {
        if (o.class_source != "cad") continue;
        ++fitted;
        double best = 0.0;
        bool same_class = false;
        for (const sim::SceneObject& so : run.scenes[static_cast<std::size_t>(o.session)].objects) {
            const double iou =
                iou_3d(sim::model_of(so).box_object.transformed(lift_to_3d(so.pose)), o.box_world);
            if (iou > best) best = iou, same_class = so.cls == *o.cls;
        }
        right += best > 0.5 && same_class;
    }
    EXPECT_GE(fitted, 6u);
    EXPECT_GE(static_cast<double>(right), 0.8 * static_cast<double>(fitted))
        << right << " of " << fitted;
    // Keyframes carry labelled objects and one point label per point.
    std::size_t labelled = 0;
    for (const auto& session : r.sessions) {
        for (const LabelledSessionKeyframe& k : session) {
            ASSERT_EQ(k.point_labels.size(), k.keyframe.cloud_sensor.size());
            ASSERT_EQ(k.point_classes.size(), k.keyframe.cloud_sensor.size());
            labelled += k.keyframe.objects.size();
            for (const LabelledObject& o : k.keyframe.objects) EXPECT_GE(o.points, 20u);
        }
    }
    EXPECT_GT(labelled, 20u);
}

// The simulator's labels and instance ids scrambled: the very same objects. A shorter drive than
// above (the claim does not depend on its length, and it runs twice, under the sanitizers too).
TEST(Labeller, TheSimulatorsLabelsDoNotReachIt) {
    const LabelRun plain = label_two_sessions(false, 40);
    const LabelRun scrambled = label_two_sessions(true, 40);
    ASSERT_GE(plain.result.objects.size(), 3u);  // something to compare: the claim is not vacuous
    ASSERT_EQ(scrambled.result.objects.size(), plain.result.objects.size());
    for (std::size_t i = 0; i < plain.result.objects.size(); ++i) {
        EXPECT_EQ(scrambled.result.objects[i].box_world.centre_m,
                  plain.result.objects[i].box_world.centre_m);
        EXPECT_EQ(scrambled.result.objects[i].model, plain.result.objects[i].model);
    }
}

}  // namespace
}  // namespace makeway::labelling
