// Recorded data through the online system: a simulated drive written as a ROS 1 bag and as a
// folder of PCD sweeps with TUM odometry, read back by the sweep sources `makeway run` uses, gives
// the same poses and the same object map as the simulator's own loop (the one bench nav's `ours`
// runs) on the same sweeps with the same wheel odometry.
#include <gtest/gtest.h>

#include <filesystem>

#include "../io/io_test_util.hpp"
#include "io/error.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"
#include "ros/bag_io.hpp"
#include "ros/sweep_source.hpp"

namespace makeway::rosio {
namespace {

namespace fs = std::filesystem;
using testing_util::fresh_dir;

struct Outcome {
    std::vector<Pose2> poses;
    std::vector<ObjectEstimate> objects;
    std::size_t keyframes = 0;
};

// The online system as `makeway run` builds it without a map: mapping a free 40 m square.
pipeline::OnlineSystemSetup mapping_setup(const pipeline::SystemParams& params, const Pose2& start,
                                          const perception::Detector& detector) {
    pipeline::OnlineSystemSetup setup;
    setup.params = params;
    setup.start = start;
    setup.map = Costmap({-20.0, -20.0}, 0.05, 800, 800);
    setup.map_kind = pipeline::MapKind::kNone;
    setup.detector = &detector;
    return setup;
}

Outcome run_source(SweepSource& source, const pipeline::SystemParams& params, const Pose2& start,
                   const perception::Detector& detector) {
    pipeline::OnlineSystem system(mapping_setup(params, start, detector));
    Outcome out;
    while (auto s = source.next()) {
        const auto step = system.process(
            {std::move(s->points), s->stamp_s, s->duration_s, s->pose_start, s->pose_end});
        out.poses.push_back(step.sweep.pose);
        out.keyframes += step.sweep.keyframe.has_value();
    }
    out.objects = system.objects();
    return out;
}

void expect_same(const Outcome& a, const Outcome& b, const std::string& what) {
    ASSERT_EQ(a.poses.size(), b.poses.size()) << what;
    double worst = 0.0;
    for (std::size_t i = 0; i < a.poses.size(); ++i) {
        worst = std::max(
            worst, std::hypot(a.poses[i].x_m - b.poses[i].x_m, a.poses[i].y_m - b.poses[i].y_m));
    }
    EXPECT_LT(worst, 1e-4) << what;
    EXPECT_EQ(a.keyframes, b.keyframes) << what;
    ASSERT_EQ(a.objects.size(), b.objects.size()) << what;
    for (std::size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].id, b.objects[i].id) << what;
        EXPECT_EQ(a.objects[i].cls, b.objects[i].cls) << what;
        EXPECT_LT((a.objects[i].box_world.centre_m - b.objects[i].box_world.centre_m).norm(), 1e-3)
            << what;
    }
}

TEST(SweepSource, BagsAndFoldersGiveTheSimulatorLoopsObjectMap) {
    const perception::Detector detector =
        perception::Detector::load(fs::path(MAKEWAY_SOURCE_DIR) / "models" / "detector.pt");
    sim::SceneGenParams g;
    g.seed = 1000033;  // held out from training
    g.density = sim::Density::kMedium;
    const sim::Scene scene = sim::generate_scene(g);
    const sim::RobotParams robot;
    const auto route =
        sim::drive_route(scene, sim::CollisionChecker(scene, sim::models_of(scene), robot), robot);
    ASSERT_TRUE(route.has_value());
    sim::SequenceParams sp;
    sp.seed = 9;
    sim::SequenceSimulator drive(scene, *route, sp);
    pipeline::SystemParams params;
    params.T_base_sensor = robot.T_robot_sensor();

    // The simulator's loop, recording as it goes.
    const fs::path dir = fresh_dir("drive");
    pipeline::OnlineSystem direct(mapping_setup(params, drive.start_pose(), detector));
    Outcome expected;
    std::vector<io::StampedPose> wheels;
    {
        BagWriter bag(dir / "drive.bag");
        for (int f = 0; f < 60; ++f) {
            const sim::SimFrame frame = drive.next();
            const auto step = direct.process({frame.points_sensor, frame.stamp_s, 0.1,
                                              frame.odometry_pose, frame.odometry_end_pose});
            expected.poses.push_back(step.sweep.pose);
            expected.keyframes += step.sweep.keyframe.has_value();
            const double t = kSimulatedEpoch_s + frame.stamp_s;
            bag.write_cloud("/velodyne_points", frame.points_sensor, t, "velodyne");
            bag.write_odometry("/odom", frame.odometry_pose, 0.0, 0.0, t, "odom", "base_link");
            bag.write_odometry("/odom", frame.odometry_end_pose, 0.0, 0.0, t + 0.1, "odom",
                               "base_link");
            char name[32];
            std::snprintf(name, sizeof(name), "%06d.pcd", f);
            io::write_point_cloud(dir / "clouds" / name, frame.points_sensor);
            wheels.push_back({frame.stamp_s, lift_to_3d(frame.odometry_pose)});
            if (f == 59)
                wheels.push_back({frame.stamp_s + 0.1,
                                  lift_to_3d(frame.odometry_end_pose)});  // the last sweep's end
        }
        bag.close();
    }
    expected.objects = direct.objects();
    ASSERT_GE(expected.keyframes, 11u);
    ASSERT_GE(expected.objects.size(), 3u)
        << "the drive must map something for the comparison to mean anything";
    io::write_tum(dir / "odometry.txt", wheels);

    SourceOptions from_bag;
    from_bag.bag = (dir / "drive.bag").string();
    const auto bag_source = open_sweep_source(from_bag);
    EXPECT_EQ(bag_source->size(), 60u);
    ASSERT_TRUE(bag_source->first_pose().has_value());
    // The odometry frame starts at the true start pose (the simulator's wheels are told it).
    EXPECT_LT(std::hypot(bag_source->first_pose()->x_m - drive.start_pose().x_m,
                         bag_source->first_pose()->y_m - drive.start_pose().y_m),
              1e-9);
    expect_same(expected, run_source(*bag_source, params, drive.start_pose(), detector), "bag");

    SourceOptions from_folder;
    from_folder.clouds = (dir / "clouds").string();
    from_folder.odometry = (dir / "odometry.txt").string();
    const auto folder_source = open_sweep_source(from_folder);
    expect_same(expected, run_source(*folder_source, params, drive.start_pose(), detector),
                "folder");
}

TEST(SweepSource, PosesThatDoNotCoverTheSweepsAreAnError) {
    const fs::path dir = fresh_dir("uncovered");
    {
        BagWriter bag(dir / "d.bag");
        PointCloud c;
        c.xyz = {{1.0f, 0.0f, 0.0f}};
        for (int k = 0; k < 3; ++k) bag.write_cloud("/velodyne_points", c, 100.0 + 0.1 * k, "v");
        bag.write_odometry("/odom", {}, 0.0, 0.0, 100.0, "odom", "base_link");
        bag.write_odometry("/odom", {0.1, 0.0, 0.0}, 0.0, 0.0, 100.15, "odom", "base_link");
        bag.close();
    }
    SourceOptions o;
    o.bag = (dir / "d.bag").string();
    const auto source = open_sweep_source(o);
    EXPECT_TRUE(source->next().has_value());  // 100.0-100.1 s: covered
    try {
        source->next();  // 100.1-100.2 s
        ADD_FAILURE();
    } catch (const io::FileError& e) {
        EXPECT_NE(std::string(e.what()).find("the odometry on /odom spans 100.000-100.150 s; sweep "
                                             "1 (100.100-100.200 s) lies outside"),
                  std::string::npos)
            << e.what();
    }
    // Folders: a TUM file shorter than the sweeps.
    fs::create_directories(dir / "clouds");
    for (int k = 0; k < 3; ++k) {
        PointCloud c;
        c.xyz = {{1.0f, 0.0f, 0.0f}};
        io::write_point_cloud(dir / "clouds" / (std::to_string(k) + ".pcd"), c);
    }
    io::write_tum(dir / "short.txt", {{0.0, Isometry3::Identity()}});
    SourceOptions f;
    f.clouds = (dir / "clouds").string();
    f.odometry = (dir / "short.txt").string();
    EXPECT_THROW(open_sweep_source(f), io::FileError);
}

TEST(SweepSource, InterpolationTakesTheShortTurnAndStaysInside) {
    const std::vector<StampedPose2> poses{{0.0, {0.0, 0.0, 3.0}}, {1.0, {1.0, 2.0, -3.0}}};
    const auto mid = interpolate_at(poses, 0.5);
    ASSERT_TRUE(mid.has_value());
    EXPECT_NEAR(mid->x_m, 0.5, 1e-12);
    EXPECT_NEAR(mid->y_m, 1.0, 1e-12);
    EXPECT_NEAR(std::abs(mid->yaw_rad), M_PI, 1e-9);  // through pi, not through 0
    EXPECT_FALSE(interpolate_at(poses, -0.01).has_value());
    EXPECT_FALSE(interpolate_at(poses, 1.01).has_value());
    EXPECT_FALSE(interpolate_at({}, 0.0).has_value());
}

}  // namespace
}  // namespace makeway::rosio
