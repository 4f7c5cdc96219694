#pragma once
// Where everything in a scene is at time t: objects (chairs move when a pusher pulls them) and
// walking people. Ground truth for every stage's tests and for the benchmarks' risk metrics.
#include <vector>

#include "makeway/common/object_estimate.hpp"
#include "makeway/common/oriented_box.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::sim {

/// The model an object is drawn with, in its object frame.
struct ObjectModel {
    TriangleMesh mesh_object;
    OrientedBox box_object;  ///< tight box of the mesh in the object frame
};

/// Procedural model from style + seed, or the user mesh. Throws std::invalid_argument for an
/// unknown style or a missing user mesh (io validates scenes before this is reached).
ObjectModel model_of(const SceneObject& object);

/// model_of() of every object of the scene, in order.
std::vector<ObjectModel> models_of(const Scene& scene);

/// Ground truth of one object at one time.
struct ObjectState {
    std::uint32_t id = 0;
    ObjectClass cls = ObjectClass::kChair;
    Isometry3 T_world_object = Isometry3::Identity();
    OrientedBox box_world;
    Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
};

/// Pose of scene.objects[index] at t_s, and its planar velocity.
Pose2 object_pose_at(const Scene& scene, std::size_t index, double t_s,
                     Eigen::Vector2d* velocity_mps = nullptr);

/// Every object at t_s; `models` is model_of() of each object, in order.
std::vector<ObjectState> object_states_at(const Scene& scene,
                                          const std::vector<ObjectModel>& models, double t_s);

/// States as the object map's type (id, class, box, velocity; existence 1), in order.
std::vector<ObjectEstimate> object_estimates(const std::vector<ObjectState>& states);

/// object_states_at() as the object map's type (object_estimates): the truth the benchmark's risk
/// metrics and the truth-fed baselines use.
std::vector<ObjectEstimate> object_estimates_at(const Scene& scene,
                                                const std::vector<ObjectModel>& models, double t_s);

/// Position of a walker at t_s [m] and heading [rad].
Eigen::Vector2d walker_position_at(const Walker& walker, double t_s, double* heading_rad = nullptr);

/// Person geometry in the person frame (origin on the floor): a cylinder body and a sphere head.
constexpr double kPersonRadius_m = 0.22;
TriangleMesh make_person_mesh();

}  // namespace makeway::sim
