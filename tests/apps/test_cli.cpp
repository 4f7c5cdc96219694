// End-to-end tests of the makeway program: config, info, convert, bad input, demo, the scene and
// simulation chain, bench sim, navigation, verification and the detector's commands.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "io/tracking_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

// `makeway config` prints the shipped file, reads a user's file back with every key, and lists
// the keys; a bad file is one line and exit 2.
TEST(Cli, ConfigPrintsDescribesAndChecks) {
    const auto dir = testing_util::fresh_dir("config");
    const CliRun shipped = run_makeway("config", dir);
    ASSERT_EQ(shipped.exit_code, 0) << shipped.err;
    EXPECT_EQ(shipped.out, io::read_file(std::string(MAKEWAY_SOURCE_DIR) + "/config/default.yaml"));
    std::ofstream(dir / "mine.yaml") << "collision_monitor:\n  latency_s: 0.3\n";
    const CliRun mine = run_makeway("config " + (dir / "mine.yaml").string(), dir);
    ASSERT_EQ(mine.exit_code, 0) << mine.err;
    EXPECT_NE(mine.out.find("  latency_s: 0.3 "), std::string::npos) << mine.out;
    EXPECT_NE(mine.out.find("  stop_padding_m: 0.04 "), std::string::npos)
        << mine.out;  // the default, filled in
    const CliRun described = run_makeway("config --describe", dir);
    ASSERT_EQ(described.exit_code, 0) << described.err;
    EXPECT_NE(described.out.find("  latency_s = 0.2"), std::string::npos) << described.out;
    EXPECT_NE(described.out.find("[0, 2] [s]  sweep age"), std::string::npos) << described.out;
    std::ofstream(dir / "bad.yaml") << "collision_monitor:\n  latency_s: 7\n";
    const CliRun bad = run_makeway("config " + (dir / "bad.yaml").string(), dir);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(lines(bad.err), 1u) << bad.err;
    EXPECT_NE(bad.err.find("collision_monitor.latency_s must be in [0, 2] (got 7)"),
              std::string::npos)
        << bad.err;
    EXPECT_TRUE(bad.out.empty()) << bad.out;
}

TEST(Cli, InfoPrintsOneJsonObject) {
    const auto dir = testing_util::fresh_dir("info");
    PointCloud c = testing_util::random_cloud(1, 100, PointFields::all());
    c.xyz[5].x() = NAN;
    io::write_point_cloud(dir / "c.pcd", c, {.pcd = io::PcdEncoding::kBinaryCompressed});
    const CliRun r = run_makeway("info " + (dir / "c.pcd").string(), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(lines(r.out), 1u);
    const io::Json j = io::Json::parse(r.out);
    EXPECT_EQ(j["format"], "pcd");
    EXPECT_EQ(j["encoding"], "binary_compressed");
    EXPECT_EQ(j["points"], 100);
    EXPECT_EQ(j["nan_count"], 1);
    EXPECT_EQ(j["fields"].size(), 8u);
    const PointBounds b = compute_bounds(c);
    EXPECT_EQ(j["bounds_m"]["min"][0].get<float>(), b.min_m.x());
    EXPECT_EQ(j["bounds_m"]["max"][2].get<float>(), b.max_m.z());
}

TEST(Cli, ConvertKeepsValuesAndWarnsAboutDroppedFields) {
    const auto dir = testing_util::fresh_dir("convert");
    const PointCloud c = testing_util::random_cloud(2, 500, PointFields::all());
    io::write_point_cloud(dir / "c.ply", c);
    CliRun r = run_makeway("convert " + (dir / "c.ply").string() + " " + (dir / "c.pcd").string() +
                               " --pcd-encoding ascii",
                           dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(testing_util::clouds_bit_equal(c, io::read_point_cloud(dir / "c.pcd").cloud));
    r = run_makeway("convert " + (dir / "c.pcd").string() + " " + (dir / "c.bin").string(), dir);
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_NE(r.err.find("cannot hold ring, time, label, instance"), std::string::npos) << r.err;
}

TEST(Cli, BadInputGivesExitTwoOneLineAndNoOutput) {
    const auto dir = testing_util::fresh_dir("bad");
    std::ofstream(dir / "trunc.pcd") << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                        "WIDTH 9\nPOINTS 9\nDATA binary\nabc";
    std::ofstream(dir / "empty.ply").close();
    PointCloud nan_cloud = testing_util::random_cloud(3, 10, {});
    nan_cloud.xyz[2].z() = INFINITY;
    io::write_point_cloud(dir / "nan.bin", nan_cloud);
    std::ofstream(dir / "bad.yaml") << "simulation:\n  frames: -1\n  colour: red\n";
    std::ofstream(dir / "scene.yaml")
        << "name: x\nobjects:\n  - {id: 1, class: chair, style: throne}\n";
    std::ofstream(dir / "route.txt") << "1 2\n3\n";
    std::ofstream(dir / "good_scene.yaml")
        << "name: empty\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n";

    const std::vector<std::pair<std::string, std::string>> cases = {
        {"convert " + (dir / "missing.pcd").string() + " " + (dir / "o1.ply").string(),
         (dir / "missing.pcd").string() + ": no such file"},
        {"convert " + (dir / "trunc.pcd").string() + " " + (dir / "o2.ply").string(),
         (dir / "trunc.pcd").string() + ": data size mismatch"},
        {"convert " + (dir / "empty.ply").string() + " " + (dir / "o3.pcd").string(),
         (dir / "empty.ply").string() + ": empty file"},
        {"convert " + (dir / "nan.bin").string() + " " + (dir / "o4.pcd").string(),
         (dir / "nan.bin").string() + ": 1 points have NaN"},
        {"convert " + (dir / "nan.bin").string() + " " + (dir / "o5.xyz").string(),
         (dir / "o5.xyz").string() + ": unknown point-cloud extension"},
        {"info " + (dir / "trunc.pcd").string(),
         (dir / "trunc.pcd").string() + ": data size mismatch"},
        {"demo --config " + (dir / "bad.yaml").string() + " --out " + (dir / "o6").string(),
         (dir / "bad.yaml").string() + ": 2 problems: "},
        {"convert --pcd-encoding zip a.pcd b.pcd", "--pcd-encoding"},
        {"simulate --scene " + (dir / "scene.yaml").string() + " --out " + (dir / "o7").string(),
         (dir / "scene.yaml").string() + ": objects[0]: unknown style 'throne'"},
        {"simulate --scene " + (dir / "good_scene.yaml").string() + " --route " +
             (dir / "route.txt").string() + " --out " + (dir / "o8").string(),
         (dir / "route.txt").string() + ": line 2: expected two numbers 'x y'"},
        {"simulate --scene " + (dir / "good_scene.yaml").string() + " --frames 0 --out " +
             (dir / "o9").string(),
         "--frames"},
        {"cad --style throne --out " + (dir / "o10.obj").string(), "--style"},
        {"scene --density crowded --out " + (dir / "o11.yaml").string(), "--density"},
        {"scene --out " + (dir / "o12.txt").string(),
         (dir / "o12.txt").string() + ": a scene file must end in .yaml"},
        {"frobnicate", "frobnicate"},
        // Numbers at the boundary (CLI11 alone saturated these seeds and let NaN through a range).
        {"scene --seed -1 --out " + (dir / "o13.yaml").string(),
         "--seed: must be a non-negative whole number"},
        {"scene --seed 1e23 --out " + (dir / "o13.yaml").string(),
         "--seed: must be a non-negative whole number"},
        {"scene --seed 99999999999999999999 --out " + (dir / "o13.yaml").string(),
         "--seed: is too large"},
        {"navigate --scene " + (dir / "good_scene.yaml").string() + " --time-limit nan --out " +
             (dir / "o14").string(),
         "--time-limit: must be a finite number"},
        {"track --detections " + dir.string() + " --min-score nan --out " + (dir / "o15").string(),
         "--min-score: must be a finite number"},
    };
    for (const auto& [args, expected] : cases) {
        const CliRun r = run_makeway(args, dir);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("makeway: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    }
    for (const char* out : {"o1.ply", "o2.ply", "o3.pcd", "o4.pcd", "o5.xyz", "o6", "o7", "o8",
                            "o9", "o10.obj", "o11.yaml", "o12.txt", "o13.yaml", "o14", "o15"}) {
        EXPECT_FALSE(std::filesystem::exists(dir / out)) << out;
    }
    EXPECT_EQ(run_makeway("convert " + (dir / "nan.bin").string() + " " +
                              (dir / "ok.pcd").string() + " --non-finite drop",
                          dir)
                  .exit_code,
              0);
    EXPECT_EQ(io::read_point_cloud(dir / "ok.pcd").cloud.size(), 9u);
}

TEST(Cli, DemoWritesItsOutputs) {
    const auto dir = testing_util::fresh_dir("demo");
    std::ofstream(dir / "small.yaml")
        << "lidar:\n  azimuth_step_deg: 1.0\nsimulation:\n  frames: 20\n";
    const CliRun r = run_makeway(
        "demo --config " + (dir / "small.yaml").string() + " --out " + (dir / "out").string(), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json s = io::read_json(dir / "out" / "summary.json");
    EXPECT_EQ(s["objects"], 34);  // the study space: 12 tables, 22 chairs
    EXPECT_EQ(s["recorded_frames"], 20);
    EXPECT_TRUE(s["format_round_trips_exact"].get<bool>());
    EXPECT_GT(s["first_sweep_points"].get<int>(), 5000);
    // The full method `ours` runs too when the default weights are in the tree (they are
    // committed).
    const bool weights = std::filesystem::exists(std::filesystem::path(MAKEWAY_SOURCE_DIR) /
                                                 "models" / "detector.pt");
    ASSERT_EQ(s["navigation"].size(), weights ? 4u : 3u);
    if (weights) {
        EXPECT_EQ(s["navigation"][3]["method"], "ours");
        // The full system's map holds the room's furniture (the study space: 34 pieces).
        EXPECT_GE(s["navigation"][3]["final_objects"].size(), 8u) << s["navigation"][3].dump();
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / "routes" / "ours.png"));
    }
    // Every method ends within 60 s of driving or says why it stopped (issue 29): all but `con`
    // (the robot taken 3x its size, for which the rows of the study space may be closed) reach the
    // goal, and one that does not stops by its own give-up rule, not by circling until the time
    // limit (`con` reaches the waypoint at about 51 s and gives up on the next leg; README, Table
    // II's nineteenth pass); the object-aware methods drive into nothing.
    for (const auto& run : s["navigation"]) {
        const std::string method = run["method"].get<std::string>();
        if (method != "con") {
            EXPECT_TRUE(run["reached_goal"].get<bool>()) << method;
        }
        EXPECT_TRUE(run["reached_goal"].get<bool>() ||
                    (run["total_time_s"].get<double>() <= 60.0 &&
                     !run["failure"].get<std::string>().empty()) ||
                    run["failure"].get<std::string>().rfind("gave up", 0) == 0)
            << run.dump();
        if (method == "gt-perc" || method == "ours") {
            EXPECT_EQ(run["robot_caused_contacts"].get<int>(), 0) << run.dump();
        }
    }
    for (const char* f :
         {"scene.yaml", "scene.png", "report.md", "routes/all_methods.png", "routes/con.png",
          "routes/oppo.png", "routes/gt-perc.png", "sequence/poses_gt.txt",
          "sequence/clouds/000010.pcd", "sequence/objects/000019.json"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out" /
                                         "sequence/clouds/000001.pcd"));  // one cloud per second
}

TEST(Cli, CadSceneSimulateChain) {
    const auto dir = testing_util::fresh_dir("chain");
    ASSERT_EQ(
        run_makeway("cad --style office_chair --seed 3 --out " + (dir / "chair.obj").string(), dir)
            .exit_code,
        0);
    EXPECT_GT(std::filesystem::file_size(dir / "chair.obj"), 1000u);
    CliRun r = run_makeway(
        "scene --seed 2 --density sparse --sessions 2 --out " + (dir / "s.yaml").string(), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"s.yaml", "s.png", "s_session1.yaml", "s_session1.png"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
    }
    r = run_makeway("simulate --scene " + (dir / "s.yaml").string() +
                        " --frames 3 --format bin --seed 4 --out " + (dir / "run").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const PointCloud c = io::read_point_cloud(dir / "run" / "clouds" / "000002.bin").cloud;
    EXPECT_GT(c.size(), 10000u);
    EXPECT_EQ(std::filesystem::file_size(dir / "run" / "labels" / "000002.label"), 4 * c.size());
    const io::Json frame = io::read_json(dir / "run" / "objects" / "000002.json");
    EXPECT_FALSE(frame["objects"].empty());
    EXPECT_NEAR(frame["stamp_s"].get<double>(), 0.2, 1e-12);
    EXPECT_EQ(io::read_tum(dir / "run" / "poses_gt.txt").size(), 3u);
    EXPECT_EQ(io::read_tum(dir / "run" / "odometry.txt").size(), 3u);
}

TEST(Cli, BenchSimPrintsItsNumbers) {
    const auto dir = testing_util::fresh_dir("bench");
    const CliRun r = run_makeway("bench sim --sweeps 1", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json j = io::Json::parse(r.out);
    for (const char* key : {"rays_per_second_1t", "rays_per_second_2t", "scan_ms"}) {
        EXPECT_GT(j[key].get<double>(), 0.0) << key;
    }
    EXPECT_EQ(j["rays_per_sweep"], 57600);
}

TEST(Cli, NavigateWritesRunRouteAndCostmap) {
    const auto dir = testing_util::fresh_dir("navigate");
    std::ofstream(dir / "room.yaml")
        << "name: room\nfloor: {min_m: [-4.5, -2.5], max_m: [4.5, 2.5]}\n"
           "walls:\n  - {a_m: [-4, -2], b_m: [4, -2]}\n  - {a_m: [4, -2], b_m: [4, 2]}\n"
           "  - {a_m: [4, 2], b_m: [-4, 2]}\n  - {a_m: [-4, 2], b_m: [-4, -2]}\n"
           "objects:\n  - {id: 1, class: chair, style: office_chair, pose: {x_m: 0, y_m: 0.3, "
           "yaw_rad: 1.57}}\n"
           "start: {x_m: -3, y_m: -0.5, yaw_rad: 0}\nwaypoint: {x_m: 0, y_m: -1.2, yaw_rad: 0}\n"
           "goal: {x_m: 3, y_m: -0.5, yaw_rad: 0}\n";
    CliRun r = run_makeway("navigate --scene " + (dir / "room.yaml").string() +
                               " --method gt-perc --out " + (dir / "run").string(),
                           dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json run = io::read_json(dir / "run" / "run.json");
    EXPECT_TRUE(run["success"].get<bool>());
    EXPECT_FALSE(run["trajectory_xyyaw"].empty());
    for (const char* f : {"route.png", "costmap.yaml", "costmap.pgm"})
        EXPECT_TRUE(std::filesystem::exists(dir / "run" / f)) << f;
    // The exported costmap serves as a static map for another run.
    r = run_makeway("navigate --scene " + (dir / "room.yaml").string() + " --map " +
                        (dir / "run" / "costmap.yaml").string() + " --method oppo --out " +
                        (dir / "run2").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_makeway("navigate --scene " + (dir / "room.yaml").string() + " --map " +
                        (dir / "nope.yaml").string() + " --out " + (dir / "run3").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find((dir / "nope.yaml").string() + ": no such file"), std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "run3"));
    EXPECT_EQ(run_makeway("navigate --scene x.yaml --method fast --out y", dir).exit_code, 2);
    // The full system with the committed weights; a missing model file is named, nothing written.
    r = run_makeway("navigate --scene " + (dir / "room.yaml").string() + " --method ours --out " +
                        (dir / "ours").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json ours = io::read_json(dir / "ours" / "run.json");
    EXPECT_EQ(ours["method"].get<std::string>(), "ours");
    EXPECT_TRUE(ours["success"].get<bool>());
    // ... and its perception found the chair where it stands (0, 0.3), from its own pose.
    bool chair_found = false;
    for (const auto& o : ours["final_objects"]) {
        const auto c = o["box_world"]["centre_m"];
        chair_found |=
            o["class"] == "chair" && std::hypot(c[0].get<double>(), c[1].get<double>() - 0.3) < 0.3;
    }
    EXPECT_TRUE(chair_found) << ours["final_objects"].dump();
    EXPECT_GT(ours["keyframes"].get<int>(), 5);
    r = run_makeway("navigate --scene " + (dir / "room.yaml").string() + " --method ours --model " +
                        (dir / "nope.pt").string() + " --out " + (dir / "ours2").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find((dir / "nope.pt").string()), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "ours2"));
}

TEST(Cli, VerifyRefinesAFlippedDetectionAndRejectsAWallBox) {
    const auto dir = testing_util::fresh_dir("verify");
    std::ofstream(dir / "room.yaml")
        << "name: room\nfloor: {min_m: [-4.5, -2.5], max_m: [4.5, 2.5]}\n"
           "walls:\n  - {a_m: [-4, -2], b_m: [4, -2]}\n  - {a_m: [4, -2], b_m: [4, 2]}\n"
           "  - {a_m: [4, 2], b_m: [-4, 2]}\n  - {a_m: [-4, 2], b_m: [-4, -2]}\n"
           "objects:\n  - {id: 1, class: chair, style: four_leg_chair, model_seed: 4, pose: {x_m: "
           "-1, y_m: 0.6, yaw_rad: 0.6}}\n"
           // The robot stands still (start = waypoint = goal): one static sweep.
           "start: {x_m: -3, y_m: -0.5, yaw_rad: 0}\nwaypoint: {x_m: -3, y_m: -0.5, yaw_rad: 0}\n"
           "goal: {x_m: -3, y_m: -0.5, yaw_rad: 0}\n";
    ASSERT_EQ(run_makeway("simulate --scene " + (dir / "room.yaml").string() +
                              " --frames 1 --out " + (dir / "sim").string(),
                          dir)
                  .exit_code,
              0);
    ASSERT_EQ(run_makeway("cad --style four_leg_chair --seed 4 --out " +
                              (dir / "cad" / "chair_four_leg.obj").string(),
                          dir)
                  .exit_code,
              0);
    ASSERT_EQ(run_makeway("cad --style office_chair --seed 9 --out " +
                              (dir / "cad" / "chair_office.obj").string(),
                          dir)
                  .exit_code,
              0);
    const Isometry3 T_world_sensor =
        io::read_tum(dir / "sim" / "poses_gt.txt").front().T_world_sensor;
    const io::Json truth = io::read_json(dir / "sim" / "objects" / "000000.json")["objects"][0];
    OrientedBox box = io::box_from_json(truth["box_world"]).transformed(T_world_sensor.inverse());
    const double true_yaw = box.yaw_rad;
    box.yaw_rad += 3.14159265358979 + 0.1;  // a detector's flip by pi
    box.centre_m.x() += 0.05;
    const OrientedBox wall{{0.0, 0.0, 0.0}, {0.5, 0.5, 0.9}, 0.0};
    io::Json dets = {
        {"detections",
         {{{"class", "chair"}, {"box", io::to_json(box)}, {"score", 0.8}},
          {{"class", "chair"}, {"box", io::to_json(wall.transformed(Isometry3::Identity()))}}}}};
    dets["detections"][1]["box"]["centre_m"] = {
        (T_world_sensor.inverse() * Eigen::Vector3d(3.95, 0.0, 0.45)).x(),
        (T_world_sensor.inverse() * Eigen::Vector3d(3.95, 0.0, 0.45)).y(), 0.0};
    io::write_json(dir / "dets.json", dets);
    const CliRun r =
        run_makeway("verify --cloud " + (dir / "sim" / "clouds" / "000000.pcd").string() +
                        " --detections " + (dir / "dets.json").string() + " --cad " +
                        (dir / "cad").string() + " --out " + (dir / "verified.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json v = io::read_json(dir / "verified.json")["verified"];
    ASSERT_EQ(v.size(), 2u);
    EXPECT_TRUE(v[0]["accepted"].get<bool>()) << v[0].dump();
    EXPECT_EQ(v[0]["model"], "chair_four_leg");
    const double yaw = v[0]["T_sensor_object"]["yaw_rad"].get<double>();
    EXPECT_LT(std::abs(std::remainder(yaw - true_yaw, 2 * 3.14159265358979)), 0.05);
    EXPECT_FALSE(v[1]["accepted"].get<bool>());
    // verify's output is track's input: the accepted chair, seen in five keyframes, becomes the one
    // object of the map.
    std::filesystem::create_directories(dir / "frames");
    for (int k = 0; k < 5; ++k) {
        io::Json frame = io::read_json(dir / "verified.json");
        frame["stamp_s"] = 0.5 * k;
        io::write_json(dir / "frames" / ("00000" + std::to_string(k) + ".json"), frame);
    }
    const CliRun t = run_makeway(
        "track --detections " + (dir / "frames").string() + " --out " + (dir / "tracks").string(),
        dir);
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto tracked = io::read_object_frame(dir / "tracks" / "000004.json");
    ASSERT_EQ(tracked.size(), 1u);
    EXPECT_EQ(tracked[0].cls, ObjectClass::kChair);
    EXPECT_LT((tracked[0].box_world.centre_m.head<2>() -
               io::box_from_json(v[0]["box"]).centre_m.head<2>())
                  .norm(),
              1e-6);
    // Bad input: a detection without a class names the file and the detection.
    std::ofstream(dir / "bad.json") << "[{\"box\": {}}]";
    const CliRun bad =
        run_makeway("verify --cloud " + (dir / "sim" / "clouds" / "000000.pcd").string() +
                        " --detections " + (dir / "bad.json").string() + " --cad " +
                        (dir / "cad").string() + " --out " + (dir / "v2.json").string(),
                    dir);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(
        bad.err.find((dir / "bad.json").string() + ": detection 0: 'class' must be chair or table"),
        std::string::npos)
        << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "v2.json"));
}

TEST(Cli, DatasetTrainDetectAndEvaluateATinyModel) {
    const auto dir = testing_util::fresh_dir("detector");
    CliRun r = run_makeway(
        "dataset --scenes 1 --seed 3 --max-keyframes 4 --keyframe-every 5 "
        "--exclude-styles none --out " +
            (dir / "data").string(),
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "data" / "clouds" / "000003.bin"));
    const io::Json meta = io::read_json(dir / "data" / "meta.json");
    EXPECT_TRUE(meta["exclude_styles"].empty());  // none: every style of the generated scenes
    EXPECT_EQ(meta["keyframes"].get<int>(), 4);
    EXPECT_GT(meta["objects"].get<int>(), 0);
    r = run_makeway("train-detector --data " + (dir / "data").string() +
                        " --epochs 2 --batch 2 --width 8 --out " + (dir / "model.pt").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(
        std::filesystem::exists(dir / "model.pt.ckpt"));  // removed once the model is written
    const std::string cloud = (dir / "data" / "clouds" / "000000.bin").string();
    r = run_makeway("detect --model " + (dir / "model.pt").string() + " --cloud " + cloud +
                        " --out " + (dir / "dets.json").string() + " --png " +
                        (dir / "dets.png").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(io::read_json(dir / "dets.json")["detections"].is_array());
    EXPECT_GT(std::filesystem::file_size(dir / "dets.png"), 1000u);
    // The picture is an output: it may not replace the cloud it shows.
    const auto cloud_bytes = std::filesystem::file_size(cloud);
    r = run_makeway("detect --model " + (dir / "model.pt").string() + " --cloud " + cloud +
                        " --out " + (dir / "d4.json").string() + " --png " + cloud,
                    dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(std::filesystem::file_size(cloud), cloud_bytes);
    EXPECT_FALSE(std::filesystem::exists(dir / "d4.json"));
    // A quick look (6 keyframes per scene): the plumbing, not the accuracy (tests/eval does that).
    r = run_makeway("eval-detection --model " + (dir / "model.pt").string() +
                        " --scenes 1 --max-keyframes 6 --out " + (dir / "eval").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json s = io::read_json(dir / "eval" / "summary.json");
    EXPECT_EQ(s["max_keyframes"], 6);
    EXPECT_GT(s["keyframes"].get<int>(), 0);
    EXPECT_LE(s["keyframes"].get<int>(), 6);
    for (const char* key : {"map_25", "map_50", "latency_ms_median_2t"})
        EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_TRUE(s["per_class"]["chair"].contains("ap_25"));
    EXPECT_TRUE(s["left_out"]["per_class"]["table"].contains("yaw_within_10deg"));
    // Issue 32: the dataset keeps each keyframe's ground plane, so the model is levelled to the
    // data's sensor height (the simulated Jackal's 0.45 m), and the evaluation scores rooms of
    // clutter alone.
    EXPECT_TRUE(io::read_json(dir / "data" / "labels" / "000000.json").contains("ground_plane"));
    EXPECT_NEAR(s["level_height_m"].get<double>(), 0.45, 0.02);
    EXPECT_GT(s["clutter"]["keyframes"].get<int>(), 0);
    EXPECT_TRUE(s["clutter"]["network_per_keyframe_at"].contains("0.5"));
    // A furniture folder without models: one line naming it, exit 2, nothing written.
    std::filesystem::create_directories(dir / "no_models");
    r = run_makeway("eval-detection --model " + (dir / "model.pt").string() +
                        " --scenes 1 --furniture " + (dir / "no_models").string() + " --out " +
                        (dir / "eval2").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find((dir / "no_models").string()), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "eval2"));
    // Bad model and bad data: one line naming the file, exit 2.
    std::ofstream(dir / "junk.pt") << "junk";
    r = run_makeway("detect --model " + (dir / "junk.pt").string() + " --cloud " +
                        (dir / "data" / "clouds" / "000000.bin").string() + " --out " +
                        (dir / "d2.json").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("makeway: " + (dir / "junk.pt").string() + ": ", 0), 0u) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "d2.json"));
    // NaN coordinates are bad input unless the user asks to drop them.
    PointCloud nan_cloud = io::read_point_cloud(dir / "data" / "clouds" / "000000.bin").cloud;
    nan_cloud.xyz[0].x() = NAN;
    io::write_point_cloud(dir / "nan.bin", nan_cloud);
    r = run_makeway("detect --model " + (dir / "model.pt").string() + " --cloud " +
                        (dir / "nan.bin").string() + " --out " + (dir / "d3.json").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find((dir / "nan.bin").string() + ": 1 points have NaN"), std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "d3.json"));
    r = run_makeway("detect --model " + (dir / "model.pt").string() + " --cloud " +
                        (dir / "nan.bin").string() + " --non-finite drop --out " +
                        (dir / "d3.json").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    r = run_makeway("train-detector --data " + (dir / "nowhere").string() + " --out " +
                        (dir / "m2.pt").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "m2.pt"));
}

}  // namespace
}  // namespace makeway
