#pragma once
// Trajectories in the TUM RGB-D format ("stamp tx ty tz qx qy qz qw") and the KITTI odometry
// format (row-major 3x4 [R|t] per line). Reads throw FileError naming the line; writes are atomic.
#include <filesystem>
#include <string_view>
#include <vector>

#include "makeway/common/transforms.hpp"

namespace makeway::io {

struct StampedPose {
    double stamp_s = 0.0;
    Isometry3 T_world_sensor = Isometry3::Identity();
};

std::vector<StampedPose> read_tum(const std::filesystem::path& path);
void write_tum(const std::filesystem::path& path, const std::vector<StampedPose>& poses);

std::vector<Isometry3> read_kitti_poses(const std::filesystem::path& path);
void write_kitti_poses(const std::filesystem::path& path, const std::vector<Isometry3>& poses);

/// Positions farther than this from the map's origin are refused wherever poses come in (TUM
/// files, odometry messages, --start): a building lies well inside 100 km of it, and 1e30 m poses
/// come from damaged data.
constexpr double kMaxPosition_m = 100e3;

/// What is wrong with a sensor mounting given by hand (x y z roll pitch yaw [m, rad]: the sensor
/// within 10 m of the base, angles within +-2 pi) or a start pose (x y yaw: within 100 km of the
/// map's origin); empty when nothing is. A 1e30 there gave poses of 1e12-1e300 m.
std::string extrinsics_problem(const std::vector<double>& xyz_rpy);
std::string start_problem(const std::vector<double>& xy_yaw);

/// Buffer parsers behind the readers (and the fuzzers). Throw FormatError.
std::vector<StampedPose> parse_tum(std::string_view text);
std::vector<Isometry3> parse_kitti_poses(std::string_view text);

}  // namespace makeway::io
