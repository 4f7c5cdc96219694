#pragma once
// JSON results (nlohmann::json): atomic writes, reads that name the file and line on error.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::io {

using Json = nlohmann::json;

/// Pretty-printed (2 spaces), atomic. Throws FileError.
void write_json(const std::filesystem::path& path, const Json& value);
/// Throws FileError on a missing file or invalid JSON.
Json read_json(const std::filesystem::path& path);

Json to_json(const OrientedBox& box);
/// Throws FormatError naming the missing or malformed key.
OrientedBox box_from_json(const Json& j);
Json to_json(const PointBounds& bounds);

}  // namespace makeway::io
