#pragma once
// The zones file (`makeway learn-zones --out zones.yaml`): learned affordance zones
// (costmap/learned_zone.hpp) as YAML a person can read, and their picture.
//
//   format: makeway_zones
//   version: 1
//   kernel_m: 0.05
//   coverage_threshold: 0.03
//   prior_strength: 10
//   chair:                      # absent: the hand-drawn zone
//     observations: 120
//     typical_size_m: [0.55, 0.55]
//     motions:                  # [dx_m, dy_m, dyaw_deg, weight] in the object's frame
//       - [0, 0, 0, 61.5]
//       - [-0.4, 0, 0, 12]
//   table: ...
#include <filesystem>
#include <string>

#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/learned_zone.hpp"

namespace makeway::io {

/// Throws FileError naming the file and every problem (one line).
costmap::LearnedZones read_zones(const std::filesystem::path& path);
/// read_zones() as an affordance layer holds it (AffordanceParams::learned); null for an empty
/// path (no zones file given: the hand-drawn zones).
std::shared_ptr<const costmap::LearnedZones> load_zones(const std::filesystem::path& path);

/// Written atomically; `header` (may be empty) becomes comment lines at the top.
void write_zones(const std::filesystem::path& path, const costmap::LearnedZones& zones,
                 const std::string& header = {});

/// Per class a panel in the object's frame: the observed motions (dots, area by weight), the
/// learned zone's coverage (shaded) and boundary (solid), the hand-drawn zone (dashed) and the
/// typical footprint.
void write_zones_png(const std::filesystem::path& path, const costmap::LearnedZones& zones,
                     const costmap::AffordanceParams& hand_drawn);

}  // namespace makeway::io
