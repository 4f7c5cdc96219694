// makeway run on recorded drives as a robot records them: a bag from `simulate --format bag` (the
// loop closes on data no one typed), the same drive as PCD files, and the bad input of real data.
#include <gtest/gtest.h>

#include <cmath>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/json_io.hpp"
#include "io/tracking_io.hpp"
#include "ros/bag_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

// A room with a chair and a table beside the robot's straight route (shared with the node's test).
void write_room(const std::filesystem::path& path) {
    std::filesystem::copy_file(
        std::filesystem::path(MAKEWAY_SOURCE_DIR) / "tests" / "data" / "room_chair_table.yaml",
        path);
}

const ObjectEstimate* nearest(const std::vector<ObjectEstimate>& objects, ObjectClass cls,
                              const Eigen::Vector2d& at, double* distance) {
    const ObjectEstimate* best = nullptr;
    *distance = 1e9;
    for (const ObjectEstimate& o : objects) {
        const double d = (o.box_world.centre_m.head<2>() - at).norm();
        if (o.cls == cls && d < *distance) *distance = d, best = &o;
    }
    return best;
}

TEST(Cli, RunOnASimulatedBagFindsTheFurnitureWhereItStands) {
    const auto dir = testing_util::fresh_dir("run_bag");
    write_room(dir / "room.yaml");
    CliRun r = run_makeway("simulate --scene " + (dir / "room.yaml").string() +
                               " --frames 60 --format bag --out " + (dir / "sim").string(),
                           dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto topics = rosio::bag_topics(dir / "sim" / "drive.bag");
    ASSERT_EQ(topics.count("/velodyne_points"), 1u);
    EXPECT_EQ(topics.at("/velodyne_points").type, "sensor_msgs/PointCloud2");
    EXPECT_EQ(topics.at("/velodyne_points").messages, 60u);
    EXPECT_EQ(topics.at("/odom").type, "nav_msgs/Odometry");
    EXPECT_EQ(topics.count("/ground_truth/odom"), 1u);
    EXPECT_EQ(topics.count("/tf_static"), 1u);

    r = run_makeway("run --bag " + (dir / "sim" / "drive.bag").string() + " --out " +
                        (dir / "run").string() + " --out-bag " + (dir / "run.bag").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("60 sweeps, 12 keyframes"), std::string::npos) << r.out;
    const auto objects = io::read_object_frame(dir / "run" / "objects.json");
    double d_chair = 0.0, d_table = 0.0;
    EXPECT_NE(nearest(objects, ObjectClass::kChair, {-1.0, 1.0}, &d_chair), nullptr);
    EXPECT_NE(nearest(objects, ObjectClass::kTable, {1.5, -1.3}, &d_table), nullptr);
    EXPECT_LT(d_chair, 0.3);
    EXPECT_LT(d_table, 0.3);
    const io::Json summary = io::read_json(dir / "run" / "summary.json");
    EXPECT_EQ(summary["verification"], "skipped: no --cad");
    EXPECT_EQ(summary["sweeps"], 60);
    EXPECT_TRUE(summary["timing_ms"]["per_sweep_ms"]["median"].is_number());
    for (const char* f : {"costmap.yaml", "costmap.pgm", "poses.txt", "map.png", "keyframes.png",
                          "objects/000011.json", "keyframes/000000.png"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / "run" / f)) << f;
    }
    const auto out_topics = rosio::bag_topics(dir / "run.bag");
    EXPECT_EQ(out_topics.at("/makeway/costmap").type, "nav_msgs/OccupancyGrid");
    EXPECT_EQ(out_topics.at("/makeway/costmap").messages, 12u);
    EXPECT_EQ(out_topics.at("/makeway/objects").type, "visualization_msgs/MarkerArray");
    EXPECT_EQ(out_topics.at("/makeway/odometry").messages, 60u);
    EXPECT_EQ(out_topics.at("/tf").type, "tf2_msgs/TFMessage");

    // The same drive as PCD files with TUM wheel odometry: the same map.
    r = run_makeway("simulate --scene " + (dir / "room.yaml").string() + " --frames 60 --out " +
                        (dir / "pcd").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_makeway("run --clouds " + (dir / "pcd" / "clouds").string() + " --odometry " +
                        (dir / "pcd" / "odometry.txt").string() + " --png-every 0 --out " +
                        (dir / "run_pcd").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto from_pcd = io::read_object_frame(dir / "run_pcd" / "objects.json");
    ASSERT_EQ(from_pcd.size(), objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
        EXPECT_LT((from_pcd[i].box_world.centre_m - objects[i].box_world.centre_m).norm(), 0.02)
            << i;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "run_pcd" / "keyframes.png"));

    // With CAD models the verification stage runs and says so.
    ASSERT_EQ(run_makeway("cad --style four_leg_chair --seed 4 --out " +
                              (dir / "cad" / "chair_four_leg.obj").string(),
                          dir)
                  .exit_code,
              0);
    ASSERT_EQ(run_makeway("cad --style rect_table --seed 2 --out " +
                              (dir / "cad" / "table_rect.obj").string(),
                          dir)
                  .exit_code,
              0);
    r = run_makeway("run --bag " + (dir / "sim" / "drive.bag").string() + " --cad " +
                        (dir / "cad").string() + " --png-every 0 --out " +
                        (dir / "run_cad").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json with_cad = io::read_json(dir / "run_cad" / "summary.json");
    EXPECT_EQ(with_cad["verification"].get<std::string>().rfind("on: 2 CAD models", 0), 0u)
        << with_cad["verification"];
    EXPECT_GT(with_cad["verified_accepted"].get<int>(), 0);
}

TEST(Cli, RunRefusesBadRecordingsWithOneLineAndNoOutput) {
    const auto dir = testing_util::fresh_dir("run_bad");
    write_room(dir / "room.yaml");
    ASSERT_EQ(run_makeway("simulate --scene " + (dir / "room.yaml").string() +
                              " --frames 6 --format bag --out " + (dir / "sim").string(),
                          dir)
                  .exit_code,
              0);
    const std::string bag = (dir / "sim" / "drive.bag").string();
    const auto expect_refused = [&](const std::string& args, const std::string& message) {
        const CliRun r = run_makeway(args + " --out " + (dir / "out").string(), dir);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "out")) << args;
    };
    expect_refused("run --bag " + bag + " --cloud-topic /points",
                   bag +
                       ": no topic /points (sensor_msgs/PointCloud2 topics in the bag: "
                       "/velodyne_points; choose one with --cloud-topic)");
    expect_refused("run --bag " + bag + " --odom-topic /ground_truth/objects",
                   "topic /ground_truth/objects holds std_msgs/String");
    expect_refused("run --bag " + (dir / "nothing.bag").string(), "nothing.bag: no such bag file");
    // Sweeps without per-point time, NaN points, poses that end before the sweeps do.
    std::filesystem::create_directories(dir / "clouds");
    std::ofstream(dir / "clouds" / "0.pcd")
        << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
           "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 0.5\n3 1 0.7\n";
    expect_refused("run --clouds " + (dir / "clouds").string(),
                   "0.pcd: no per-point time field (time, t or timestamp)");
    std::ofstream(dir / "clouds" / "0.pcd") << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z time\nSIZE "
                                               "4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                                               "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
                                               "2\nDATA ascii\n1 2 nan 0\n3 1 0.7 0.05\n";
    expect_refused("run --clouds " + (dir / "clouds").string(),
                   "0.pcd: 1 points have NaN or infinite coordinates");
    std::ofstream(dir / "clouds" / "1.pcd")
        << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z time\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 "
           "1\n"
           "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n3 1 0.7 0.05\n";
    std::ofstream(dir / "one_pose.txt") << "0.0 0 0 0 0 0 0 1\n";
    expect_refused("run --clouds " + (dir / "clouds").string() + " --odometry " +
                       (dir / "one_pose.txt").string() + " --non-finite drop",
                   "one_pose.txt: holds 1 poses for 2 sweeps");
    std::ofstream(dir / "late.txt") << "1767225600.5 0 0 0 0 0 0 1\n1767225601.5 1 0 0 0 0 0 1\n";
    expect_refused("run --bag " + bag + " --poses " + (dir / "late.txt").string(),
                   "late.txt: the poses span 1767225600.500-1767225601.500 s; sweep 0");
    expect_refused("run --bag " + bag + " --clouds " + (dir / "clouds").string(), "excludes");
    expect_refused("run", "give --clouds DIR or --bag FILE");
    // Poses by hand beyond any robot (issue 34: 1e30 gave poses of 1e12-1e300 m).
    expect_refused("run --bag " + bag + " --extrinsics 1e30 0 0 0 0 0",
                   "--extrinsics: the sensor lies 1e+30 m from the base (at most 10 m)");
    expect_refused("run --bag " + bag + " --start 1e30 0 0",
                   "--start: the start lies 1e+30 m from the origin (at most 100 km)");
    expect_refused("run --bag " + bag + " --start 0 0 90",
                   "--start: yaw 90 is beyond +-2 pi (radians, not degrees)");
    // Per-point times a bag would be refused for (issue 34): NaN, and 1e9 s (a wrong unit).
    std::filesystem::create_directories(dir / "clouds_t");
    const std::string header =
        "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z time\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
        "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n";
    std::ofstream(dir / "clouds_t" / "0.pcd") << header << "1 2 0.5 nan\n3 1 0.7 0.05\n";
    expect_refused("run --clouds " + (dir / "clouds_t").string(),
                   "0.pcd: the per-point time holds a non-finite value");
    std::ofstream(dir / "clouds_t" / "0.pcd") << header << "1 2 0.5 0\n3 1 0.7 1e9\n";
    expect_refused("run --clouds " + (dir / "clouds_t").string(),
                   "0.pcd: the per-point times span 1000000000.000000 s, more than 1.0 s");
}

}  // namespace
}  // namespace makeway
