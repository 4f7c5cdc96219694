#include "makeway/sim/clutter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "makeway/sim/mesh_primitives.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::sim {
namespace {

using V3 = Eigen::Vector3d;

void add_sofa(TriangleMesh& m, Rng& rng) {
    const double length = uniform(rng, 1.4, 2.2), depth = uniform(rng, 0.8, 0.95);
    const double seat = uniform(rng, 0.38, 0.48), top = uniform(rng, 0.7, 0.9);
    const double arm = uniform(rng, 0.12, 0.22), back = uniform(rng, 0.15, 0.25);
    add_box(m, V3(0, 0, seat / 2), V3(depth, length, seat));  // x: depth, y: length
    add_box(m, V3(-depth / 2 + back / 2, 0, top / 2), V3(back, length, top));
    const double arm_h = uniform(rng, seat + 0.1, top);
    for (double s : {-1.0, 1.0})
        add_box(m, V3(0, s * (length / 2 - arm / 2), arm_h / 2), V3(depth, arm, arm_h));
}

void add_shelf(TriangleMesh& m, Rng& rng) {
    const double width = uniform(rng, 0.7, 1.3), depth = uniform(rng, 0.28, 0.45);
    const double height = uniform(rng, 1.0, 2.0);
    const int boards = static_cast<int>(uniform_int(rng, 3, 5));
    for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
            add_box(m, V3(sx * (depth / 2 - 0.02), sy * (width / 2 - 0.02), height / 2),
                    V3(0.04, 0.04, height));
        }
    }
    for (int b = 0; b < boards; ++b) {
        const double z = 0.05 + (height - 0.08) * b / (boards - 1);
        add_box(m, V3(0, 0, z), V3(depth, width, 0.03));
    }
    if (bernoulli(rng, 0.5))  // a back panel
        add_box(m, V3(-depth / 2 + 0.01, 0, height / 2), V3(0.02, width, height));
}

void add_standing_person(TriangleMesh& m, Rng& rng) {
    const double h = uniform(rng, 1.55, 1.9), s = h / 1.75;
    const double stance = uniform(rng, 0.08, 0.14);
    for (double side : {-1.0, 1.0})
        add_cylinder(m, V3(0, side * stance, 0), 0.07 * s, 0.85 * s, 10);
    add_box(m, V3(0, 0, 1.13 * s), V3(0.24 * s, 0.42 * s, 0.58 * s));
    add_sphere(m, V3(0, 0, 1.6 * s), 0.11 * s, 10);
    for (double side : {-1.0, 1.0})  // arms hanging
        add_box(m, V3(0, side * 0.26 * s, 1.1 * s), V3(0.08 * s, 0.08 * s, 0.6 * s));
}

}  // namespace

std::string_view to_string(ClutterKind kind) {
    static constexpr std::array<std::string_view, kClutterKinds> kNames{
        "crate", "cabinet", "bin", "sofa", "shelf", "plant", "person", "lamp", "boxes"};
    return kNames[static_cast<std::size_t>(kind)];
}

TriangleMesh make_clutter(ClutterKind kind, Rng& rng) {
    TriangleMesh m;
    switch (kind) {
        case ClutterKind::kCrate: {
            const V3 size(uniform(rng, 0.35, 0.8), uniform(rng, 0.35, 0.8), uniform(rng, 0.3, 0.8));
            add_box(m, V3(0, 0, size.z() / 2), size);
            break;
        }
        case ClutterKind::kCabinet: {
            const V3 size(uniform(rng, 0.4, 0.65), uniform(rng, 0.5, 1.2), uniform(rng, 0.8, 1.9));
            add_box(m, V3(0, 0, size.z() / 2), size);
            break;
        }
        case ClutterKind::kBin:
            add_cylinder(m, V3::Zero(), uniform(rng, 0.14, 0.3), uniform(rng, 0.3, 0.9), 16);
            break;
        case ClutterKind::kSofa:
            add_sofa(m, rng);
            break;
        case ClutterKind::kShelf:
            add_shelf(m, rng);
            break;
        case ClutterKind::kPlant: {
            const double pot_h = uniform(rng, 0.25, 0.5), pot_r = uniform(rng, 0.12, 0.25);
            add_cylinder(m, V3::Zero(), pot_r, pot_h, 12);
            const double r = uniform(rng, 0.25, 0.5);
            add_sphere(m, V3(0, 0, pot_h + r * 0.9), r, 12);
            break;
        }
        case ClutterKind::kPerson:
            add_standing_person(m, rng);
            break;
        case ClutterKind::kLamp: {
            const double h = uniform(rng, 1.3, 1.8);
            add_cylinder(m, V3::Zero(), uniform(rng, 0.12, 0.2), 0.04, 12);
            add_cylinder(m, V3::Zero(), 0.015, h, 8);
            add_cylinder(m, V3(0, 0, h), uniform(rng, 0.15, 0.25), 0.25, 12);
            break;
        }
        case ClutterKind::kBoxes: {
            const int n = static_cast<int>(uniform_int(rng, 2, 3));
            double z = 0.0;
            for (int i = 0; i < n; ++i) {
                const V3 size(uniform(rng, 0.3, 0.6), uniform(rng, 0.3, 0.6),
                              uniform(rng, 0.2, 0.45));
                add_box(m,
                        V3(uniform(rng, -0.05, 0.05), uniform(rng, -0.05, 0.05), z + size.z() / 2),
                        size, uniform(rng, -0.3, 0.3));
                z += size.z();
            }
            break;
        }
    }
    return m;
}

namespace {

struct Disc {
    Eigen::Vector2d centre;
    double radius;
};

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * d)).norm();
}

}  // namespace

int add_clutter(Scene& scene, const ClutterParams& params, std::uint64_t seed) {
    Rng rng = make_rng(seed, 0xC1077u);
    // Everything already on the floor as discs (furniture footprints by their boxes' half
    // diagonals): a conservative test, which is all placement needs.
    std::vector<Disc> taken;
    for (const SceneObject& o : scene.objects) {
        const ObjectModel model = model_of(o);
        const Eigen::Vector2d c = to_isometry(o.pose) * model.box_object.centre_m.head<2>();
        taken.push_back({c, 0.5 * model.box_object.size_m.head<2>().norm()});
    }
    for (const Pose2& p : {scene.start, scene.waypoint, scene.goal})
        taken.push_back({Eigen::Vector2d(p.x_m, p.y_m), params.mission_gap_m});
    int placed = 0;
    for (int i = 0; i < params.count; ++i) {
        const auto kind = static_cast<ClutterKind>(uniform_int(rng, 0, kClutterKinds - 1));
        TriangleMesh mesh = make_clutter(kind, rng);
        double radius = 0.0;  // of the disc about the origin that holds the whole footprint
        for (const Eigen::Vector3f& v : mesh.vertices_m)
            radius = std::max(radius, static_cast<double>(v.head<2>().norm()));
        for (int attempt = 0; attempt < params.attempts_per_item; ++attempt) {
            const double margin = radius + params.object_gap_m;
            if (scene.floor_max_m.x() - scene.floor_min_m.x() < 2 * margin ||
                scene.floor_max_m.y() - scene.floor_min_m.y() < 2 * margin)
                break;
            const Eigen::Vector2d c(
                uniform(rng, scene.floor_min_m.x() + margin, scene.floor_max_m.x() - margin),
                uniform(rng, scene.floor_min_m.y() + margin, scene.floor_max_m.y() - margin));
            const bool clear =
                std::none_of(
                    taken.begin(), taken.end(),
                    [&](const Disc& d) { return (d.centre - c).norm() < d.radius + margin; }) &&
                std::none_of(scene.walls.begin(), scene.walls.end(),
                             [&](const Wall& w) {
                                 return segment_distance(c, w.a_m, w.b_m) <
                                        margin + 0.5 * w.thickness_m;
                             }) &&
                std::none_of(scene.pillars.begin(), scene.pillars.end(), [&](const Pillar& p) {
                    return (p.centre_m - c).norm() < margin + 0.5 * p.size_m.norm();
                });
            if (!clear) continue;
            const double yaw = uniform(rng, -std::numbers::pi, std::numbers::pi);
            transform_mesh(mesh, make_T_xyz_yaw(Eigen::Vector3d(c.x(), c.y(), 0.0), yaw));
            EnvironmentMesh e;
            e.mesh_file = "clutter:" + std::string(to_string(kind));
            e.mesh_world = std::make_shared<const TriangleMesh>(std::move(mesh));
            scene.environment.push_back(std::move(e));
            taken.push_back({c, radius});
            ++placed;
            break;
        }
    }
    return placed;
}

}  // namespace makeway::sim
