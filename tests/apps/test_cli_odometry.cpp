// makeway odometry on a recording as `makeway simulate` writes it (clouds with per-point time,
// wheel odometry in TUM), scored against the recording's ground truth; and its bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/pose_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

TEST(Cli, OdometryFollowsARecordedDrive) {
    const auto dir = testing_util::fresh_dir("odometry");
    ASSERT_EQ(run_makeway("scene --seed 5 --density dense --out " + (dir / "s.yaml").string(), dir)
                  .exit_code,
              0);
    ASSERT_EQ(run_makeway("simulate --scene " + (dir / "s.yaml").string() + " --frames 60 --out " +
                              (dir / "rec").string(),
                          dir)
                  .exit_code,
              0);
    const auto truth = io::read_tum(dir / "rec" / "poses_gt.txt");
    // The robot is told where it starts: the base under the first sweep's sensor.
    const Pose2 start = project_to_plane(truth.front().T_world_sensor);
    const std::string start_arg = std::to_string(start.x_m) + " " + std::to_string(start.y_m) +
                                  " " + std::to_string(start.yaw_rad);
    const CliRun r =
        run_makeway("odometry --clouds " + (dir / "rec" / "clouds").string() + " --odometry " +
                        (dir / "rec" / "odometry.txt").string() + " --start " + start_arg +
                        " --out " + (dir / "poses.txt").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote 60 sensor poses"), std::string::npos) << r.out;
    const auto poses = io::read_tum(dir / "poses.txt");
    ASSERT_EQ(poses.size(), truth.size());
    double worst = 0.0, travelled = 0.0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        worst = std::max(
            worst, (poses[k].T_world_sensor.translation() - truth[k].T_world_sensor.translation())
                       .head<2>()
                       .norm());
        EXPECT_DOUBLE_EQ(poses[k].stamp_s, truth[k].stamp_s);
        if (k > 0)
            travelled +=
                (truth[k].T_world_sensor.translation() - truth[k - 1].T_world_sensor.translation())
                    .norm();
    }
    EXPECT_GT(travelled, 2.0);
    EXPECT_LT(worst, 0.03) << "over " << travelled << " m";

    // Bad input: one line, exit 2, no output.
    for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
             {"odometry --clouds " + dir.string() + " --out " + (dir / "o1.txt").string(),
              "no .pcd, .ply or .bin sweeps"},
             {"odometry --clouds " + (dir / "rec" / "clouds").string() + " --odometry " +
                  (dir / "s.yaml").string() + " --out " + (dir / "o2.txt").string(),
              (dir / "s.yaml").string()}}) {
        const CliRun bad = run_makeway(args, dir);
        EXPECT_EQ(bad.exit_code, 2) << args << "\n" << bad.err;
        EXPECT_EQ(lines(bad.err), 1u) << bad.err;
        EXPECT_NE(bad.err.find(expected), std::string::npos) << bad.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "o1.txt"));
    EXPECT_FALSE(std::filesystem::exists(dir / "o2.txt"));
}

}  // namespace
}  // namespace makeway
