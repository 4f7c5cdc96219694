#pragma once
// The ray-casting world: the scene's static structure (floor, ceiling, walls, pillars) and its
// moving parts (furniture, people) as Embree instances whose poses follow the scene's time.
#include <cstdint>
#include <memory>
#include <vector>

#include "makeway/common/semantic_label.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::sim {

/// Instance ids of people in labelled clouds: kPersonInstanceBase + walker index.
constexpr std::uint32_t kPersonInstanceBase = 1000000;

struct RayHit {
    bool hit = false;
    float range_m = 0.0f;
    SemanticLabel label = SemanticLabel::kUnlabelled;
    std::uint32_t instance = 0;
    /// Diffuse reflectivity of the surface hit (0..255, Velodyne's calibrated scale): its
    /// material's, which says nothing about what the surface belongs to (see SurfaceMaterials).
    float reflectivity = 0.0f;
    float cos_incidence = 1.0f;  ///< |cos| of the angle between the ray and the surface normal
};

/// Surface materials: every surface (each wall and pillar, the floor, the ceiling, each person,
/// each furniture part) draws its material from one distribution shared by every class, as in a
/// real building (wood, fabric, metal, plastic and paint on chairs, tables and walls alike), so
/// that intensity says no more about the class than a real sensor's does. Furniture has a frame
/// material and a surface material; each of its parts (a box of 12 triangles, or a cylinder's
/// share) takes one of the two. Seeded by the scene's seed: the same room looks the same in every
/// drive through it.
/// One draw from the shared material distribution (0..255): a material type, then its spread.
float draw_reflectivity(std::uint64_t seed, std::uint64_t surface);

class World {
  public:
    /// `models[i]` is the model of scene.objects[i] (model_of()).
    World(const Scene& scene, std::vector<ObjectModel> models);
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Moves furniture and people to where they are at t_s.
    void set_time(double t_s);
    double time_s() const { return time_s_; }

    /// Whether hits carry the surface's reflectivity and incidence (the intensity model's inputs);
    /// off, they are left at their defaults and their draws skipped. On by default.
    void set_surface_model(bool on);

    /// First hit along a ray (direction need not be unit; range is along the unit direction).
    RayHit cast(const Eigen::Vector3f& origin_m, const Eigen::Vector3f& direction,
                float max_range_m) const;

    /// kPacketSize rays from one origin at once (an Embree ray packet); `directions` must be unit
    /// vectors; `valid[i]` false skips ray i.
    static constexpr int kPacketSize = 16;
    void cast_packet(const Eigen::Vector3f& origin_m, const Eigen::Vector3f* directions,
                     float max_range_m, const bool* valid, RayHit* hits) const;

    const Scene& scene() const { return scene_; }
    const std::vector<ObjectModel>& models() const { return models_; }
    std::size_t num_triangles() const { return num_triangles_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    Scene scene_;
    std::vector<ObjectModel> models_;
    double time_s_ = -1.0;
    std::size_t num_triangles_ = 0;
};

/// The scene's walls and pillars as boxes, world frame.
TriangleMesh wall_and_pillar_mesh(const Scene& scene);
/// The scene's static structure (walls, pillars and environment meshes), world frame.
TriangleMesh structure_mesh(const Scene& scene);

}  // namespace makeway::sim
