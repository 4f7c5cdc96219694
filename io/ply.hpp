#pragma once
// PLY point clouds: the vertex element of ascii, binary_little_endian and binary_big_endian files.
// Other elements (faces, ...) are skipped on read.
#include <string>
#include <string_view>

#include "io/cloud_file.hpp"

namespace makeway::io {

enum class PlyEncoding { kAscii, kBinaryLittleEndian };

/// Parses a whole PLY file held in memory. Throws FormatError saying what is wrong.
CloudFile parse_ply(std::string_view bytes);

/// Serialises every channel the cloud carries as vertex properties.
std::string serialize_ply(const PointCloud& cloud, PlyEncoding encoding);

}  // namespace makeway::io
