#pragma once
// Procedural indoor scenes: rooms with walls, door gaps and pillars; tables with chairs left around
// them the way people leave them; free-standing chairs; people; a start, a waypoint and a goal.
// Every scene returned has a collision-free start and a route for the robot's footprint
// (start -> waypoint -> goal).
#include <optional>
#include <string>

#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::sim {

enum class Density { kSparse, kMedium, kDense };
enum class Layout { kRandom, kStudySpace };

std::optional<Density> parse_density(std::string_view name);
std::optional<Layout> parse_layout(std::string_view name);
std::string_view to_string(Density density);

struct SceneGenParams {
    std::uint64_t seed = 0;
    Density density = Density::kMedium;
    Layout layout = Layout::kRandom;  ///< kStudySpace: the paper's room of 12 tables and 22 chairs
    bool people = true;               ///< walkers and chair pushers
    UsageProfile usage = UsageProfile::kDefault;  ///< how make_session moves the furniture
    int max_attempts = 40;                        ///< layouts tried before giving up
    RobotParams robot;
};

/// Throws std::runtime_error when no navigable layout was found within max_attempts.
Scene generate_scene(const SceneGenParams& params);

/// The same building on another recording session, the furniture moved by the scene's usage
/// profile (scene.hpp) from where it stands in `base`, which is session 0. Seeded by the scene's
/// seed and the session; a draw that overlaps objects or blocks the route is drawn again (20
/// times, then `base`).
Scene make_session(const Scene& base, int session, const RobotParams& robot = {});

/// Whether the start pose is collision-free and the mission route exists at t = 0.
bool is_navigable(const Scene& scene, const RobotParams& robot);

}  // namespace makeway::sim
