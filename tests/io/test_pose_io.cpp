#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/pose_io.hpp"
#include "io_test_util.hpp"
#include "makeway/common/random.hpp"

namespace makeway::io {
namespace {

std::vector<StampedPose> random_trajectory(std::size_t n) {
    Rng rng = make_rng(9);
    std::vector<StampedPose> out;
    for (std::size_t i = 0; i < n; ++i) {
        StampedPose p;
        p.stamp_s = 1700000000.0 + 0.1 * static_cast<double>(i) + uniform(rng, 0, 1e-3);
        const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
        p.T_world_sensor.linear() = q.toRotationMatrix();
        p.T_world_sensor.translation() =
            Eigen::Vector3d(normal(rng, 0, 10), normal(rng, 0, 10), 0.4);
        out.push_back(p);
    }
    return out;
}

TEST(PoseIo, TumRoundTrip) {
    const auto dir = testing_util::fresh_dir("tum");
    const auto poses = random_trajectory(50);
    write_tum(dir / "t.txt", poses);
    const auto back = read_tum(dir / "t.txt");
    ASSERT_EQ(back.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
        EXPECT_EQ(back[i].stamp_s, poses[i].stamp_s);  // shortest round-trip text: exact
        EXPECT_EQ(back[i].T_world_sensor.translation(), poses[i].T_world_sensor.translation());
        EXPECT_TRUE(back[i].T_world_sensor.isApprox(poses[i].T_world_sensor, 1e-12));
    }
}

TEST(PoseIo, KittiRoundTrip) {
    const auto dir = testing_util::fresh_dir("kitti");
    std::vector<Isometry3> poses;
    for (const auto& p : random_trajectory(20)) poses.push_back(p.T_world_sensor);
    write_kitti_poses(dir / "k.txt", poses);
    const auto back = read_kitti_poses(dir / "k.txt");
    ASSERT_EQ(back.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) EXPECT_TRUE(back[i].isApprox(poses[i], 1e-12));
}

TEST(PoseIo, TumAcceptsCommentsAndBlankLines) {
    const auto poses =
        parse_tum("# header\n\n0.0 1 2 3 0 0 0 1\n  \n0.1 1 2 3 0 0 0.7071068 0.7071068\n");
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_NEAR(yaw_of(poses[1].T_world_sensor), 1.5707963267948966, 1e-6);
}

TEST(PoseIo, BadInputSaysWhichLine) {
    const std::vector<std::pair<std::string, std::string>> tum_cases = {
        {"0 1 2 3 0 0 0\n", "line 1: expected 8 numbers, found 7"},
        {"0 1 2 3 0 0 0 1\n1 nan 2 3 0 0 0 1\n", "line 2: value is NaN"},
        {"0 1 2 3 0 0 0 2\n", "line 1: quaternion norm"},
        {"1 1 2 3 0 0 0 1\n0 1 2 3 0 0 0 1\n", "line 2: timestamp goes backwards"},
        {"0 1 2 x 0 0 0 1\n", "line 1: bad number 'x'"},
        {"# only a comment\n", "no poses"},
        // Recordings from the wild (issue 34): stamps all alike, ~1e300 or negative; poses of 1e30
        // m.
        {"0 1 2 3 0 0 0 1\n0 1 2 3 0 0 0 1\n", "line 2: timestamp 0 repeats the line before's"},
        {"1e300 1 2 3 0 0 0 1\n", "line 1: timestamp 1e+300 is not seconds in [0, 1e10]"},
        {"-5 1 2 3 0 0 0 1\n", "line 1: timestamp -5 is not seconds"},
        {"0 1e30 2 3 0 0 0 1\n", "line 1: position 1e+30 m from the origin (more than 100 km)"},
    };
    for (const auto& [text, expected] : tum_cases) {
        try {
            parse_tum(text);
            ADD_FAILURE() << text << " accepted";
        } catch (const FormatError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(parse_kitti_poses("1 0 0 0 0 1 0 0 0 0 1\n"), FormatError);
    EXPECT_THROW(parse_kitti_poses("2 0 0 0 0 1 0 0 0 0 1 0\n"), FormatError);   // not a rotation
    EXPECT_THROW(parse_kitti_poses("-1 0 0 0 0 1 0 0 0 0 1 0\n"), FormatError);  // reflection
    const auto dir = testing_util::fresh_dir("bad");
    std::ofstream(dir / "p.txt") << "0 1 2 3 0 0 0\n";
    try {
        read_tum(dir / "p.txt");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()),
                  (dir / "p.txt").string() + ": line 1: expected 8 numbers, found 7");
    }
}

}  // namespace
}  // namespace makeway::io
