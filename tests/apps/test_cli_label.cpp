// makeway label on two recorded sessions of one room (the chair moved between them), and the round
// trip of its output into train-detector.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/dataset_io.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

TEST(Cli, LabelTwoSessionsAndTrainOnTheLabels) {
    const auto dir = testing_util::fresh_dir("label");
    namespace fs = std::filesystem;
    std::ifstream in(fs::path(MAKEWAY_SOURCE_DIR) / "tests" / "data" / "room_chair_table.yaml");
    std::stringstream room;
    room << in.rdbuf();
    std::ofstream(dir / "room.yaml") << room.str();
    std::string moved = room.str();
    const std::string chair = "pose: {x_m: -1, y_m: 1.0, yaw_rad: 0.6}";
    ASSERT_NE(moved.find(chair), std::string::npos);
    moved.replace(moved.find(chair), chair.size(), "pose: {x_m: 0.2, y_m: 1.5, yaw_rad: 1.4}");
    std::ofstream(dir / "room2.yaml") << moved;
    for (const char* s : {"room", "room2"}) {
        const CliRun r =
            run_makeway("simulate --scene " + (dir / (std::string(s) + ".yaml")).string() +
                            " --frames 50 --out " + (dir / s).string(),
                        dir);
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    ASSERT_EQ(run_makeway("cad --style four_leg_chair --seed 4 --out " +
                              (dir / "cad" / "chair_a.obj").string(),
                          dir)
                  .exit_code,
              0);
    ASSERT_EQ(
        run_makeway(
            "cad --style rect_table --seed 2 --out " + (dir / "cad" / "table_a.obj").string(), dir)
            .exit_code,
        0);

    CliRun r =
        run_makeway("label --sessions " + (dir / "room").string() + " " + (dir / "room2").string() +
                        " --cad " + (dir / "cad").string() + " --out " + (dir / "labels").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("session 2 aligned to session 1"), std::string::npos) << r.out;
    const io::Json meta = io::read_json(dir / "labels" / "meta.json");
    EXPECT_EQ(meta["keyframes"], 20);
    EXPECT_GT(meta["point_classes"]["movable"].get<int>(), 500);
    // Both pieces of furniture in both sessions, each where it stood in that session.
    const io::Json objects = io::read_json(dir / "labels" / "objects.json")["objects"];
    auto found = [&](int session, const std::string& cls, double x, double y) {
        for (const io::Json& o : objects) {
            const OrientedBox b = io::box_from_json(o["box_world"]);
            if (o["session"] == session && o["class"] == cls &&
                (b.centre_m.head<2>() - Eigen::Vector2d(x, y)).norm() < 0.1)
                return true;
        }
        return false;
    };
    EXPECT_TRUE(found(0, "chair", -1.0, 1.0)) << objects.dump();
    EXPECT_TRUE(found(1, "chair", 0.2, 1.5)) << objects.dump();
    EXPECT_TRUE(found(0, "table", 1.5, -1.3)) << objects.dump();
    EXPECT_TRUE(found(1, "table", 1.5, -1.3)) << objects.dump();
    // The dataset layout makeway dataset writes, read back as training data; one label per point.
    const std::vector<LabelledKeyframe> data = io::read_detection_dataset(dir / "labels");
    ASSERT_EQ(data.size(), 20u);
    std::size_t labelled = 0;
    for (std::size_t k = 0; k < data.size(); ++k) {
        labelled += data[k].objects.size();
        EXPECT_EQ(fs::file_size(dir / "labels" / "point_labels" / (io::frame_name(k) + ".label")),
                  4 * data[k].cloud_sensor.size());
    }
    EXPECT_GE(labelled, 20u);
    r = run_makeway("train-detector --data " + (dir / "labels").string() +
                        " --epochs 1 --batch 2 --width 8 --out " + (dir / "model.pt").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "model.pt"));

    // Recorded sweeps with poses from elsewhere (here makeway odometry's): the labeller's odometry
    // does not run, and the same furniture comes out.
    for (const char* s : {"room", "room2"}) {
        ASSERT_EQ(run_makeway("odometry --clouds " + (dir / s / "clouds").string() +
                                  " --odometry " + (dir / s / "odometry.txt").string() + " --out " +
                                  (dir / s / "poses.txt").string(),
                              dir)
                      .exit_code,
                  0);
    }
    r = run_makeway("label --sessions " + (dir / "room").string() + " " + (dir / "room2").string() +
                        " --poses-name poses.txt --cad " + (dir / "cad").string() + " --out " +
                        (dir / "labels_poses").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json with_poses = io::read_json(dir / "labels_poses" / "objects.json")["objects"];
    EXPECT_EQ(with_poses.size(), objects.size()) << with_poses.dump();

    // Without CAD models the moved chair is still an object (Movable), and the previous round's
    // detector (the default weights) names its class; the table never moved and no model says what
    // it is: it stays background.
    r = run_makeway("label --sessions " + (dir / "room").string() + " " + (dir / "room2").string() +
                        " --model " +
                        (fs::path(MAKEWAY_SOURCE_DIR) / "models" / "detector.pt").string() +
                        " --out " + (dir / "labels_net").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json net = io::read_json(dir / "labels_net" / "objects.json")["objects"];
    bool chair_by_detector = false;
    for (const io::Json& o : net) {
        const OrientedBox b = io::box_from_json(o["box_world"]);
        if (o["session"] == 0 && (b.centre_m.head<2>() - Eigen::Vector2d(-1.0, 1.0)).norm() < 0.2) {
            chair_by_detector = o["class"] == "chair" && o["class_source"] == "detector";
        }
    }
    EXPECT_TRUE(chair_by_detector) << net.dump();

    // Bad input: one line naming the path, exit 2, nothing written.
    r = run_makeway("label --sessions " + (dir / "room").string() + " " +
                        (dir / "nowhere").string() + " --out " + (dir / "l2").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find((dir / "nowhere").string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "l2"));
}

}  // namespace
}  // namespace makeway
