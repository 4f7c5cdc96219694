#pragma once
// PCD v0.7 (the Point Cloud Library's format): ascii, binary and binary_compressed (LZF) data.
#include <string>
#include <string_view>

#include "io/cloud_file.hpp"

namespace makeway::io {

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

/// Parses a whole PCD file held in memory. Throws FormatError saying what is wrong.
CloudFile parse_pcd(std::string_view bytes);

/// Serialises every channel the cloud carries.
std::string serialize_pcd(const PointCloud& cloud, PcdEncoding encoding);

}  // namespace makeway::io
