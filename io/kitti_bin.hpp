#pragma once
// KITTI Velodyne scans (.bin): consecutive float32 x, y, z, intensity, little endian.
#include <string>
#include <string_view>

#include "io/cloud_file.hpp"

namespace makeway::io {

/// Throws FormatError when the size is not a multiple of 16 bytes.
CloudFile parse_kitti_bin(std::string_view bytes);

/// Writes x, y, z and intensity (0 when the cloud has none); other channels cannot be stored.
std::string serialize_kitti_bin(const PointCloud& cloud);

}  // namespace makeway::io
