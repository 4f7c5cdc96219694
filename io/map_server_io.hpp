#pragma once
// Costmaps and static maps in the ROS map_server format: an 8-bit binary PGM image and a YAML file
// (image, resolution, origin, negate, occupied_thresh, free_thresh, mode).
#include <filesystem>
#include <string>
#include <string_view>

#include "makeway/common/costmap.hpp"

namespace makeway::io {

/// Writes NAME.yaml and NAME.pgm beside it (mode "scale": pixel = 255 - cost * 255 / 254, unknown
/// 205, so lethal is black). Atomic; throws FileError.
void write_map_server(const std::filesystem::path& yaml_path, const Costmap& costmap);

/// Reads a map_server map as a static map: occupancy above occupied_thresh is lethal, below
/// free_thresh free, else unknown. Throws FileError naming the YAML or the image.
Costmap read_map_server(const std::filesystem::path& yaml_path);

/// A binary (P5) 8-bit PGM: width, height and pixels (first row = top). Throws FormatError.
struct PgmImage {
    int width = 0;
    int height = 0;
    std::string pixels;
};
PgmImage parse_pgm(std::string_view bytes);
std::string serialize_pgm(const PgmImage& image);

}  // namespace makeway::io
