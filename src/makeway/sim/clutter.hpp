#pragma once
// Things of furniture size that are not furniture (issue 32): crates, cabinets, bins, sofas,
// shelves, plants, standing people, floor lamps, stacked boxes. The detector must learn that they
// are neither chairs nor tables, and its false positives on them are measured, so scenes carry
// them as static environment meshes: the LiDAR sees them, nothing labels them, the robot's route
// goes around them.
#include <cstdint>
#include <string_view>

#include "makeway/common/random.hpp"
#include "makeway/common/triangle_mesh.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::sim {

enum class ClutterKind : std::uint8_t {
    kCrate,    ///< a closed box, 0.35-0.8 m
    kCabinet,  ///< a tall closed box, 0.8-1.9 m high
    kBin,      ///< a cylinder, 0.3-0.9 m high
    kSofa,     ///< a seat block, a back and two arms, 1.4-2.2 m long
    kShelf,    ///< four posts and 3-5 boards, open at the front
    kPlant,    ///< a pot and a ball of foliage
    kPerson,   ///< standing still: two legs, a torso, a head
    kLamp,     ///< a base, a thin pole and a shade
    kBoxes,    ///< two or three boxes stacked
};
constexpr int kClutterKinds = 9;
std::string_view to_string(ClutterKind kind);

/// A random instance of `kind` in its own frame: standing on z = 0, centred on the origin, at most
/// about 2.2 m across.
TriangleMesh make_clutter(ClutterKind kind, Rng& rng);

struct ClutterParams {
    int count = 6;               ///< items tried per scene (fewer where the floor is full)
    double object_gap_m = 0.25;  ///< free space kept to furniture footprints and walls
    double mission_gap_m = 1.2;  ///< free space kept around the start, waypoint and goal
    int attempts_per_item = 40;  ///< random positions tried per item
};

/// Adds up to params.count clutter items (kinds and poses drawn from `seed`) to scene.environment,
/// each on free floor: clear of the furniture's footprints (at time 0), walls, pillars, earlier
/// clutter and the mission's poses. Returns how many were placed. The route may still be blocked:
/// callers that need one check it and drop items from the back.
int add_clutter(Scene& scene, const ClutterParams& params, std::uint64_t seed);

}  // namespace makeway::sim
