#pragma once
// JSON results (nlohmann::json): atomic writes, reads that name the file and line on error.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::io {

using Json = nlohmann::json;

/// Pretty-printed (2 spaces), atomic. Throws FileError.
void write_json(const std::filesystem::path& path, const Json& value);
/// Throws FileError on a missing file or invalid JSON.
Json read_json(const std::filesystem::path& path);
/// Text of a JSON value; bytes that are not UTF-8 become U+FFFD instead of throwing.
std::string dump_json(const Json& value, int indent = -1);

Json to_json(const OrientedBox& box);
/// Throws FormatError naming the missing or malformed key.
OrientedBox box_from_json(const Json& j);
Json to_json(const PointBounds& bounds);
/// A pose as {"t_m": [x, y, z], "q_wxyz": [w, x, y, z]}.
Json pose_to_json(const Isometry3& T);
/// Reads {"t_m", "q_wxyz"} or the planar {"t_m", "yaw_rad"}; throws FormatError naming `name` when
/// malformed, non-finite or not a unit quaternion.
Isometry3 pose_from_json(const Json& j, const std::string& name = "pose");

}  // namespace makeway::io
