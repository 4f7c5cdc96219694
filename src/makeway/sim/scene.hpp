#pragma once
// An indoor scene as plain data: the building (floor, walls with door gaps, pillars), the
// furniture, the people, and the robot's mission (start, waypoint, goal). Scenes are YAML files a
// person can read and edit (io/scene_io); everything else in sim/ is computed from this.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "makeway/common/semantic_label.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/triangle_mesh.hpp"

namespace makeway::sim {

/// A straight wall from a_m to b_m (its centre line), standing on the floor.
struct Wall {
    Eigen::Vector2d a_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d b_m = Eigen::Vector2d::Zero();
    double thickness_m = 0.15;
    double height_m = 2.8;
};

/// A rectangular pillar, axis-aligned.
struct Pillar {
    Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d size_m = Eigen::Vector2d(0.4, 0.4);
    double height_m = 2.8;
};

/// A chair or table: either a procedural model (style + model_seed) or a user mesh.
struct SceneObject {
    std::uint32_t id = 0;  ///< instance id, > 0, unique in the scene
    ObjectClass cls = ObjectClass::kChair;
    std::string style;             ///< furniture style name; empty for a user mesh
    std::uint64_t model_seed = 0;  ///< dimensions of the procedural model
    std::string mesh_file;         ///< user mesh (OBJ/PLY/STL/DAE), relative to the scene file
    double scale = 1.0;            ///< applied to a user mesh (on top of its units)
    std::string units = "m";       ///< a user mesh's length unit: m, cm, mm, in, ft
    std::string up_axis =
        "z";  ///< a user mesh's up (Collada files are turned Z-up by their own declaration first)
    std::string forward_axis =
        "x";  ///< a user mesh's front (where a sitter faces; a table's length)
    bool recentre =
        true;  ///< a user mesh's footprint centred on its origin, its lowest point on the floor
    /// The loaded user mesh in its object frame (scaled); filled by io when the scene is read.
    std::shared_ptr<const TriangleMesh> user_mesh;
    Pose2 pose;                  ///< T_world_object on the floor at time 0
    std::uint32_t table_id = 0;  ///< the table a chair belongs to, 0 for none
};

/// Static geometry from a mesh of any size and no class: a scanned room (PLY/OBJ from RGB-D or
/// LiDAR mapping), a building's model. The LiDAR sees it as structure; its parts between the
/// robot's ground clearance and its top are obstacles the robot must not touch, like walls.
struct EnvironmentMesh {
    std::string mesh_file;  ///< OBJ/PLY/STL/DAE, relative to the scene file
    double scale = 1.0;
    std::string units = "m";
    std::string up_axis = "z";
    std::string forward_axis = "x";
    bool recentre = false;  ///< a scan's own frame is kept by default (origin and floor height)
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< T_world_mesh: translation ...
    Eigen::Vector3d rpy_rad = Eigen::Vector3d::Zero();     ///< ... and roll, pitch, yaw
    /// The loaded mesh in the world frame (placed, then posed); filled by io when the scene is
    /// read.
    std::shared_ptr<const TriangleMesh> mesh_world;
};

/// A person walking a closed route at constant speed.
struct Walker {
    std::vector<Eigen::Vector2d> route_m;  ///< closed polyline, at least 2 points
    double speed_mps = 1.0;
    double phase_s = 0.0;  ///< time offset along the route
};

/// A person who pulls a chair out from its table and pushes it back, along the chair's forward
/// axis: the chair's offset is -pull_m * (1 - cos(2 pi (t + phase) / period)) / 2 along its x.
struct ChairPusher {
    std::uint32_t chair_id = 0;
    double period_s = 8.0;
    double pull_m = 0.4;
    double phase_s = 0.0;
};

/// What Scene::validate() accepts at most.
constexpr double kMaxFloorExtent_m = 200.0;
/// Walls, pillars, furniture and walkers' routes lie on the floor or at most this far beyond it
/// (a wall 2000 km long made the simulator allocate until it failed).
constexpr double kMaxBeyondFloor_m = 10.0;
constexpr std::size_t kMaxStructures = 10000, kMaxObjects = 2000, kMaxWalkers = 200;
/// Triangles of all environment meshes together (a room scan decimated for a robot's simulator).
constexpr std::size_t kMaxEnvironmentTriangles = 5000000;

/// How the people of a building leave its furniture between recording sessions (make_session):
/// each session draws every object's pose anew from its pose in the base scene (session 0).
///  - default: half the chairs pushed in (up to 0.15 m) or pulled out (up to 0.45 m) along their
///    axis and turned (12 deg sd); 15 % of the tables shifted (0.25 m sd) with their chairs.
///  - pulled_back: 70 % of the chairs pulled straight back 0.35-0.9 m (3 deg sd); tables stay.
///  - sideways: 60 % of the chairs swung out to one side (50-100 deg) and slid 0.25-0.5 m that
///    way and 0.1-0.35 m back; tables stay.
///  - tables_nudged: 60 % of the tables slid 0.2-0.6 m along their length either way and turned
///    (8 deg sd), their chairs with them; 30 % of the chairs as in default.
enum class UsageProfile { kDefault, kPulledBack, kSideways, kTablesNudged };
/// The profiles' names, in the enum's order (scene files, --usage).
const std::vector<std::string>& usage_profile_names();
std::optional<UsageProfile> parse_usage_profile(std::string_view name);
std::string_view to_string(UsageProfile profile);

struct Scene {
    std::string name = "scene";
    std::uint64_t seed = 0;
    std::string density = "medium";
    UsageProfile usage = UsageProfile::kDefault;  ///< how sessions move the furniture
    Eigen::Vector2d floor_min_m = Eigen::Vector2d(-10, -10);
    Eigen::Vector2d floor_max_m = Eigen::Vector2d(10, 10);
    double ceiling_height_m = 2.8;
    std::vector<Wall> walls;
    std::vector<Pillar> pillars;
    std::vector<EnvironmentMesh> environment;
    std::vector<SceneObject> objects;
    std::vector<Walker> walkers;
    std::vector<ChairPusher> pushers;
    Pose2 start, waypoint, goal;

    /// Whether (x, y) lies on the room's floor (floor_min_m .. floor_max_m, inclusive).
    bool on_floor(const Eigen::Vector2d& xy) const {
        return (xy.array() >= floor_min_m.array()).all() &&
               (xy.array() <= floor_max_m.array()).all();
    }

    /// Every structural problem (duplicate ids, a pusher of a missing chair, ...); empty if valid.
    std::vector<std::string> validate() const;
};

}  // namespace makeway::sim
