#include "makeway/sim/world.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "makeway/common/random.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::sim {
namespace {

RTCGeometry make_triangle_geometry(RTCDevice device, const TriangleMesh& mesh) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices_m.size()));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
        for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh.vertices_m[i][k];
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k)
            indices[3 * t + k] = static_cast<unsigned>(mesh.triangles[t][k]);
    }
    rtcCommitGeometry(geom);
    return geom;
}

void set_instance_pose(RTCGeometry inst, const Isometry3& T) {
    float xfm[12];  // 3x4 column major
    const Eigen::Matrix4d m = T.matrix();
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 3; ++r) xfm[3 * c + r] = static_cast<float>(m(r, c));
    }
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(inst);
}

// Surfaces are told apart by their triangles in groups of 12 (one box: a wall, a pillar, a leg).
constexpr unsigned kTrianglesPerPart = 12;

// Surface keys for the material draws: one range per kind of surface, so no two collide.
constexpr std::uint64_t kFloorSurface = 1, kCeilingSurface = 2;
std::uint64_t structure_surface(unsigned part) { return (1ULL << 32) + part; }
std::uint64_t object_surface(std::uint32_t instance, int which) {
    return (2ULL << 32) + 2ULL * instance + static_cast<std::uint64_t>(which);
}

}  // namespace

float draw_reflectivity(std::uint64_t seed, std::uint64_t surface) {
    // Typical calibrated reflectivities of indoor materials (Velodyne scale): fabric and dark
    // plastic low, wood and paint middle, light paint and bare metal high. Every class of surface
    // draws from this one list.
    struct Material {
        float lo, hi;
    };
    static constexpr Material kMaterials[] = {
        {5.0f, 30.0f},    // fabric, upholstery
        {15.0f, 45.0f},   // dark plastic, rubber
        {25.0f, 60.0f},   // wood, laminate
        {40.0f, 85.0f},   // paint, plaster
        {60.0f, 120.0f},  // light paint, bare and brushed metal
    };
    constexpr int kCount = static_cast<int>(sizeof(kMaterials) / sizeof(kMaterials[0]));
    const int type =
        std::min(kCount - 1, static_cast<int>(counter_uniform(seed, 2 * surface) * kCount));
    const Material& m = kMaterials[type];
    return m.lo + static_cast<float>(counter_uniform(seed, 2 * surface + 1)) * (m.hi - m.lo);
}

TriangleMesh wall_and_pillar_mesh(const Scene& scene) {
    TriangleMesh m;
    for (const Wall& w : scene.walls) {
        const Eigen::Vector2d d = w.b_m - w.a_m;
        const Eigen::Vector2d c = 0.5 * (w.a_m + w.b_m);
        add_box(m, Eigen::Vector3d(c.x(), c.y(), w.height_m / 2),
                Eigen::Vector3d(d.norm() + w.thickness_m, w.thickness_m, w.height_m),
                std::atan2(d.y(), d.x()));
    }
    for (const Pillar& p : scene.pillars) {
        add_box(m, Eigen::Vector3d(p.centre_m.x(), p.centre_m.y(), p.height_m / 2),
                Eigen::Vector3d(p.size_m.x(), p.size_m.y(), p.height_m));
    }
    return m;
}

TriangleMesh structure_mesh(const Scene& scene) {
    TriangleMesh m = wall_and_pillar_mesh(scene);
    for (const EnvironmentMesh& e : scene.environment) {
        if (e.mesh_world) m.append(*e.mesh_world);
    }
    return m;
}

struct World::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> object_scenes;
    RTCScene person_scene = nullptr;
    std::vector<unsigned> object_inst_ids;
    std::vector<unsigned> person_inst_ids;
    std::vector<SemanticLabel> geom_labels;  // static geometry id -> label
    std::vector<std::pair<SemanticLabel, std::uint32_t>>
        inst_labels;                             // instance geometry id -> label
    std::vector<Eigen::Matrix3f> inst_rotation;  // instance geometry id -> R_world_object now
    std::uint64_t material_seed = 0;
    bool surface_model = true;

    // Ng is Embree's unnormalised geometric normal, in the object frame for instances.
    RayHit to_hit(unsigned geom_id, unsigned inst_id, unsigned prim_id, float t,
                  const Eigen::Vector3f& Ng, const Eigen::Vector3f& direction) const {
        RayHit h;
        if (geom_id == RTC_INVALID_GEOMETRY_ID) return h;
        h.hit = true;
        h.range_m = t;
        const unsigned part = prim_id / kTrianglesPerPart;
        Eigen::Vector3f normal = Ng;
        if (inst_id != RTC_INVALID_GEOMETRY_ID) {
            h.label = inst_labels[inst_id].first;
            h.instance = inst_labels[inst_id].second;
            if (!surface_model) return h;
            normal = inst_rotation[inst_id] * Ng;
            // A part takes the frame or the surface material of its object.
            const int which =
                static_cast<int>(counter_uniform(material_seed ^ h.instance, part) < 0.5);
            h.reflectivity = draw_reflectivity(material_seed, object_surface(h.instance, which));
        } else {
            h.label = geom_labels[geom_id];
            if (!surface_model) return h;
            const std::uint64_t surface = h.label == SemanticLabel::kGround ? kFloorSurface
                                          : h.label == SemanticLabel::kCeiling
                                              ? kCeilingSurface
                                              : structure_surface(part);
            h.reflectivity = draw_reflectivity(material_seed, surface);
        }
        const float n = normal.norm(), d = direction.norm();
        h.cos_incidence = n > 0.0f && d > 0.0f ? std::abs(normal.dot(direction)) / (n * d) : 1.0f;
        return h;
    }
};

World::World(const Scene& scene, std::vector<ObjectModel> models)
    : impl_(std::make_unique<Impl>()), scene_(scene), models_(std::move(models)) {
    if (models_.size() != scene_.objects.size())
        throw std::invalid_argument("World: one model per object");
    Impl& w = *impl_;
    w.material_seed = scene_.seed * 0x9E3779B97F4A7C15ULL + 0x6D617465726961ULL;  // "materia"
    w.device = rtcNewDevice(nullptr);
    if (!w.device) throw std::runtime_error("Embree device creation failed");
    w.top = rtcNewScene(w.device);
    rtcSetSceneBuildQuality(w.top, RTC_BUILD_QUALITY_LOW);  // rebuilt whenever something moves

    auto attach_static = [&](const TriangleMesh& mesh, SemanticLabel label) {
        if (mesh.triangles.empty()) return;
        RTCGeometry g = make_triangle_geometry(w.device, mesh);
        const unsigned id = rtcAttachGeometry(w.top, g);
        rtcReleaseGeometry(g);
        if (w.geom_labels.size() <= id) w.geom_labels.resize(id + 1);
        w.geom_labels[id] = label;
        w.inst_labels.resize(std::max<std::size_t>(w.inst_labels.size(), id + 1));
        num_triangles_ += mesh.triangles.size();
    };
    const Eigen::Vector2d lo = scene_.floor_min_m, hi = scene_.floor_max_m;
    TriangleMesh floor, ceiling;
    add_box(floor, Eigen::Vector3d((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2, -0.05),
            Eigen::Vector3d(hi.x() - lo.x(), hi.y() - lo.y(), 0.1));
    add_box(ceiling,
            Eigen::Vector3d((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2,
                            scene_.ceiling_height_m + 0.05),
            Eigen::Vector3d(hi.x() - lo.x(), hi.y() - lo.y(), 0.1));
    attach_static(floor, SemanticLabel::kGround);
    attach_static(ceiling, SemanticLabel::kCeiling);
    attach_static(structure_mesh(scene_), SemanticLabel::kStructure);

    auto attach_instance = [&](RTCScene child, SemanticLabel label, std::uint32_t instance) {
        RTCGeometry inst = rtcNewGeometry(w.device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, child);
        rtcSetGeometryTimeStepCount(inst, 1);
        set_instance_pose(inst, Isometry3::Identity());
        const unsigned id = rtcAttachGeometry(w.top, inst);
        rtcReleaseGeometry(inst);
        w.inst_labels.resize(std::max<std::size_t>(w.inst_labels.size(), id + 1));
        w.geom_labels.resize(std::max<std::size_t>(w.geom_labels.size(), id + 1));
        w.inst_labels[id] = {label, instance};
        w.inst_rotation.resize(w.inst_labels.size(), Eigen::Matrix3f::Identity());
        return id;
    };
    for (std::size_t i = 0; i < models_.size(); ++i) {
        RTCScene child = rtcNewScene(w.device);
        rtcSetSceneBuildQuality(child,
                                RTC_BUILD_QUALITY_HIGH);  // built once, traversed millions of times
        RTCGeometry g = make_triangle_geometry(w.device, models_[i].mesh_object);
        rtcAttachGeometry(child, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(child);
        w.object_scenes.push_back(child);
        w.object_inst_ids.push_back(
            attach_instance(child, to_semantic_label(scene_.objects[i].cls), scene_.objects[i].id));
        num_triangles_ += models_[i].mesh_object.triangles.size();
    }
    if (!scene_.walkers.empty()) {
        const TriangleMesh person = make_person_mesh();
        w.person_scene = rtcNewScene(w.device);
        RTCGeometry g = make_triangle_geometry(w.device, person);
        rtcAttachGeometry(w.person_scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(w.person_scene);
        for (std::size_t k = 0; k < scene_.walkers.size(); ++k) {
            w.person_inst_ids.push_back(
                attach_instance(w.person_scene, SemanticLabel::kPerson,
                                kPersonInstanceBase + static_cast<std::uint32_t>(k)));
            num_triangles_ += person.triangles.size();
        }
    }
    set_time(0.0);
}

World::~World() {
    if (!impl_) return;
    if (impl_->top) rtcReleaseScene(impl_->top);
    for (RTCScene s : impl_->object_scenes) rtcReleaseScene(s);
    if (impl_->person_scene) rtcReleaseScene(impl_->person_scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

void World::set_surface_model(bool on) { impl_->surface_model = on; }

void World::set_time(double t_s) {
    if (t_s == time_s_) return;
    const bool first = time_s_ < 0.0;
    time_s_ = t_s;
    if (!first && scene_.pushers.empty() && scene_.walkers.empty()) return;  // nothing moves
    Impl& w = *impl_;
    for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
        const Isometry3 T_world_object = lift_to_3d(object_pose_at(scene_, i, t_s));
        set_instance_pose(rtcGetGeometry(w.top, w.object_inst_ids[i]), T_world_object);
        w.inst_rotation[w.object_inst_ids[i]] = T_world_object.linear().cast<float>();
    }
    for (std::size_t k = 0; k < scene_.walkers.size(); ++k) {
        double heading = 0.0;
        const Eigen::Vector2d p = walker_position_at(scene_.walkers[k], t_s, &heading);
        const Isometry3 T_world_person =
            make_T_xyz_yaw(Eigen::Vector3d(p.x(), p.y(), 0.0), heading);
        set_instance_pose(rtcGetGeometry(w.top, w.person_inst_ids[k]), T_world_person);
        w.inst_rotation[w.person_inst_ids[k]] = T_world_person.linear().cast<float>();
    }
    rtcCommitScene(w.top);
}

RayHit World::cast(const Eigen::Vector3f& origin_m, const Eigen::Vector3f& direction,
                   float max_range_m) const {
    const Eigen::Vector3f d = direction.normalized();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin_m.x();
    rh.ray.org_y = origin_m.y();
    rh.ray.org_z = origin_m.z();
    rh.ray.dir_x = d.x();
    rh.ray.dir_y = d.y();
    rh.ray.dir_z = d.z();
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = max_range_m;
    rh.ray.mask = static_cast<unsigned>(-1);  // Debian's Embree has ray masks on
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->top, &context, &rh);
    return impl_->to_hit(rh.hit.geomID, rh.hit.instID[0], rh.hit.primID, rh.ray.tfar,
                         {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}, d);
}

void World::cast_packet(const Eigen::Vector3f& origin_m, const Eigen::Vector3f* directions,
                        float max_range_m, const bool* valid, RayHit* hits) const {
    static_assert(kPacketSize == 16, "the packet type below is RTCRayHit16");
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, neighbouring directions
    alignas(64) int valid_mask[kPacketSize];
    alignas(64) RTCRayHit16 rh;
    for (int i = 0; i < kPacketSize; ++i) {
        valid_mask[i] = valid[i] ? -1 : 0;
        rh.ray.org_x[i] = origin_m.x();
        rh.ray.org_y[i] = origin_m.y();
        rh.ray.org_z[i] = origin_m.z();
        rh.ray.dir_x[i] = directions[i].x();
        rh.ray.dir_y[i] = directions[i].y();
        rh.ray.dir_z[i] = directions[i].z();
        rh.ray.tnear[i] = 0.0f;
        rh.ray.tfar[i] = max_range_m;
        rh.ray.mask[i] = static_cast<unsigned>(-1);
        rh.ray.time[i] = 0.0f;
        rh.ray.flags[i] = 0;
        rh.ray.id[i] = static_cast<unsigned>(i);
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid_mask, impl_->top, &context, &rh);
    for (int i = 0; i < kPacketSize; ++i) {
        hits[i] = valid[i]
                      ? impl_->to_hit(
                            rh.hit.geomID[i], rh.hit.instID[0][i], rh.hit.primID[i], rh.ray.tfar[i],
                            {rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]}, directions[i])
                      : RayHit{};
    }
}

}  // namespace makeway::sim
