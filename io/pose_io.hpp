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

/// Buffer parsers behind the readers (and the fuzzers). Throw FormatError.
std::vector<StampedPose> parse_tum(std::string_view text);
std::vector<Isometry3> parse_kitti_poses(std::string_view text);

}  // namespace makeway::io
