#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <tuple>

#include "makeway/common/angles.hpp"
#include "makeway/common/polygon2d.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/pipeline/pipeline.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::pipeline {
namespace {

namespace fs = std::filesystem;

const fs::path kWeights = fs::path(MAKEWAY_SOURCE_DIR) / "models" / "detector.pt";

// What one drive of the online system gave: the final map, the objects as they stood at the last
// sweep, where keyframes were made, and what verification did.
struct ChainRun {
    std::vector<ObjectEstimate> objects;
    std::vector<sim::ObjectState> truth;
    std::vector<Eigen::Vector2d> path;
    std::size_t detections = 0, accepted = 0, from_seed = 0;
    /// Per mapped chair (by id), its yaw error [rad] in the first keyframe's map that held it on
    /// a true chair.
    std::map<std::uint32_t, double> first_chair_yaw_error;
};

// The yaw error [rad] of a mapped chair against the true chair within 0.3 m (none: no such chair).
std::optional<double> chair_yaw_error(const ObjectEstimate& o,
                                      const std::vector<sim::ObjectState>& truth) {
    if (o.cls != ObjectClass::kChair) return std::nullopt;
    for (const sim::ObjectState& t : truth) {
        if (t.cls == ObjectClass::kChair &&
            (o.box_world.centre_m.head<2>() - t.box_world.centre_m.head<2>()).norm() < 0.3)
            return std::abs(angle_diff(o.box_world.yaw_rad, t.box_world.yaw_rad));
    }
    return std::nullopt;
}

// The whole online system with the committed weights on a simulated drive it never trained on
// (held-out seed, honest intensity, the robot moving during every sweep), with the scene's CAD
// models or none.
ChainRun run_chain(const perception::Detector& detector, SystemParams params, bool with_cad,
                   int frames) {
    sim::SceneGenParams g;
    g.seed = 1000021;  // held out: training seeds stay below 1000000
    g.density = sim::Density::kDense;
    g.people = false;
    const sim::Scene scene = sim::generate_scene(g);
    const sim::RobotParams robot;
    const auto route =
        sim::drive_route(scene, sim::CollisionChecker(scene, sim::models_of(scene), robot), robot);
    EXPECT_TRUE(route.has_value());
    if (!route) return {};
    sim::SequenceParams sp;
    sp.seed = 5;
    // Exact wheel odometry isolates perception: with the default drift (2 cm/m, 0.01 rad/sqrt(m))
    // this drive's map objects land 0.3-0.7 m from the truth, which is the LiDAR odometry's job
    // (bench nav measures what drift costs the full system).
    sp.odometry = {0.0, 0.0, 0.0};
    sim::SequenceSimulator drive(scene, *route, sp);
    params.T_base_sensor = robot.T_robot_sensor();
    const verification::CadLibrary cad = eval::scene_cad_library(scene);
    Pipeline pipeline(params, drive.start_pose(), &detector, with_cad ? &cad : nullptr);
    ChainRun run;
    for (int f = 0; f < frames && !drive.reached_goal(); ++f) {
        const sim::SimFrame frame = drive.next();
        const SweepResult r =
            pipeline.process_sweep({frame.points_sensor, frame.stamp_s, 0.1, frame.odometry_pose,
                                    frame.odometry_end_pose});
        if (r.keyframe) {
            run.detections += r.keyframe->detections.size();
            for (const verification::VerifiedDetection& v : r.keyframe->verified) {
                run.accepted += v.accepted;
                run.from_seed += v.from_seed;
            }
            run.path.emplace_back(frame.true_pose.x_m, frame.true_pose.y_m);
            for (const ObjectEstimate& o : r.objects) {
                if (run.first_chair_yaw_error.count(o.id)) continue;
                if (const auto e = chair_yaw_error(o, frame.objects))
                    run.first_chair_yaw_error[o.id] = *e;
            }
        }
        run.objects = r.objects;
        run.truth = frame.objects;
    }
    return run;
}

// The final map holds the furniture the robot passed, where it stands, and little else.
TEST(FullChain, FindsTheFurnitureWhereItStands) {
    ASSERT_TRUE(fs::exists(kWeights)) << "the default weights are committed: " << kWeights;
    const perception::Detector detector = perception::Detector::load(kWeights);
    // A trained network on an empty keyframe: nothing (it does fire below, so this says something).
    EXPECT_TRUE(detector.detect(PointCloud{}).empty());
    SystemParams params;
    params.verify.reseed_tolerance_m =
        0.005;  // re-verification from the map's fits (off by default)
    const ChainRun run = run_chain(detector, params, true, 120);
    const auto& [objects, truth, path] = std::tie(run.objects, run.truth, run.path);
    const std::size_t detections = run.detections, accepted = run.accepted,
                      from_seed = run.from_seed;
    ASSERT_GT(detections, 10u);
    // Objects the map has verified are re-verified from their last fit with one ICP (most of the
    // accepted detections after the first keyframes); the map's precision and recall below hold.
    EXPECT_GE(static_cast<double>(from_seed), 0.3 * static_cast<double>(accepted))
        << from_seed << " of " << accepted << " from seeds";
    RecordProperty("accepted", static_cast<int>(accepted));
    RecordProperty("from_seed", static_cast<int>(from_seed));
    // Precision: every object in the map is a real one of its class, where it stands.
    int correct = 0;
    for (const ObjectEstimate& o : objects) {
        for (const sim::ObjectState& t : truth) {
            const bool near =
                (o.box_world.centre_m.head<2>() - t.box_world.centre_m.head<2>()).norm() < 0.3;
            if (near && o.cls == t.cls) {
                ++correct;
                break;
            }
        }
    }
    // Recall: the furniture within 3 m of where the robot made keyframes.
    int passed = 0, found = 0;
    for (const sim::ObjectState& t : truth) {
        double closest = 1e9;
        for (const Eigen::Vector2d& p : path)
            closest = std::min(closest, (p - t.box_world.centre_m.head<2>()).norm());
        if (closest > 3.0) continue;
        ++passed;
        for (const ObjectEstimate& o : objects) {
            if ((o.box_world.centre_m.head<2>() - t.box_world.centre_m.head<2>()).norm() < 0.3 &&
                o.cls == t.cls) {
                ++found;
                break;
            }
        }
    }
    ASSERT_GT(passed, 3) << truth.size() << " objects, " << path.size() << " keyframes";
    ASSERT_FALSE(objects.empty());
    EXPECT_GE(static_cast<double>(correct) / static_cast<double>(objects.size()), 0.8)
        << correct << " of " << objects.size() << " map objects are real";
    EXPECT_GE(static_cast<double>(found) / static_cast<double>(passed), 0.6)
        << found << " of " << passed << " passed objects found";
    // What the collision monitor gets of the CAD fits (ObjectEstimate::parts_world): the map's
    // objects carry their models' body-height parts, and those lie inside the true objects' boxes.
    int with_parts = 0, part_points = 0, inside = 0;
    for (const ObjectEstimate& o : objects) {
        if (o.parts_world.empty()) continue;
        ++with_parts;
        for (const sim::ObjectState& t : truth) {
            if ((o.box_world.centre_m.head<2>() - t.box_world.centre_m.head<2>()).norm() >= 0.3 ||
                o.cls != t.cls)
                continue;
            const auto c = t.box_world.bev_corners();
            const Polygon2 box(c.begin(), c.end());
            for (const Polygon2& part : o.parts_world) {
                for (const Eigen::Vector2d& q : part) {
                    ++part_points;
                    inside += convex_distance(box, q) <= 0.05;
                }
            }
            break;
        }
    }
    EXPECT_GE(with_parts, 0.8 * static_cast<double>(objects.size()));
    ASSERT_GT(part_points, 0);
    EXPECT_GE(inside, 0.95 * part_points) << inside << " of " << part_points << " part vertices";
    RecordProperty("map_objects", static_cast<int>(objects.size()));
    RecordProperty("with_parts", with_parts);
    RecordProperty("correct", correct);
    RecordProperty("passed", passed);
    RecordProperty("found", found);
}

// Without CAD models the map keeps the network's boxes, chairs turned to their back rests' yaw
// (verification/back_yaw.hpp): more of the mapped chairs face within 10 deg of the truth than
// with the network's yaw alone, the median error is lower, and more face right in the final map
// than in the first map that held each.
TEST(FullChain, WithoutCadModelsChairsFaceWhereTheirBacksSay) {
    ASSERT_TRUE(fs::exists(kWeights)) << "the default weights are committed: " << kWeights;
    const perception::Detector detector = perception::Detector::load(kWeights);
    // Each mapped chair's yaw error against the true chair it stands on (chairs have no symmetry).
    auto chair_errors = [](const ChainRun& run) {
        std::vector<double> e;
        for (const ObjectEstimate& o : run.objects) {
            if (const auto err = chair_yaw_error(o, run.truth)) e.push_back(*err);
        }
        return e;
    };
    auto within_10deg = [](const std::vector<double>& e) {
        return static_cast<double>(std::count_if(
                   e.begin(), e.end(), [](double x) { return x <= 10.0 * kPi / 180.0; })) /
               static_cast<double>(e.size());
    };
    SystemParams backs, network;
    network.back_yaw.enabled = false;
    const ChainRun with_backs = run_chain(detector, backs, false, 120);
    const std::vector<double> turned = chair_errors(with_backs);
    const std::vector<double> as_detected = chair_errors(run_chain(detector, network, false, 120));
    ASSERT_GE(turned.size(), 5u);
    ASSERT_GE(as_detected.size(), 5u);
    RecordProperty("chairs", static_cast<int>(turned.size()));
    RecordProperty("within_10deg_backs", std::to_string(within_10deg(turned)));
    RecordProperty("within_10deg_network", std::to_string(within_10deg(as_detected)));
    // Measured: 30 of 38 chairs within 10 deg against 29, median 2.2 against 2.0 deg. (Before the
    // map averaged a standing chair's views, MotionPrior::rest_yaw_rate_sigma_radps, 31 against
    // 26 and 2.9 against 5.5: the average now removes most of what the backs removed on this
    // drive; on eval-detection's held-out scenes the backs still add 6.7 points, README.)
    EXPECT_GE(within_10deg(turned), within_10deg(as_detected));
    EXPECT_GE(within_10deg(turned), 0.75);
    // Over keyframes: a chair's yaw in the final map against its yaw in the first map that held
    // it (each later view fused, the back seen from more sides).
    std::vector<double> first, last;
    for (const ObjectEstimate& o : with_backs.objects) {
        const auto e = chair_yaw_error(o, with_backs.truth);
        const auto it = with_backs.first_chair_yaw_error.find(o.id);
        if (!e || it == with_backs.first_chair_yaw_error.end()) continue;
        first.push_back(it->second);
        last.push_back(*e);
    }
    ASSERT_GE(first.size(), 5u);
    RecordProperty("within_10deg_first_map", std::to_string(within_10deg(first)));
    // Measured: 27 of 38 chairs within 10 deg in their first map, 30 in the final one, median
    // errors 2.6 and 2.2 deg (before the views were averaged: 25 and 31, 1.9 and 2.9 deg).
    EXPECT_GE(within_10deg(last), within_10deg(first) + 0.05);
    EXPECT_LT(median(last), median(first));
}

}  // namespace
}  // namespace makeway::pipeline
