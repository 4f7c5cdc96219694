#include "io/scene_png.hpp"

#include <algorithm>
#include <cmath>

#include "io/top_down_png.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::io {

void draw_structure(Canvas& canvas, const sim::Scene& scene) {
    const Rgb colour = label_colour(SemanticLabel::kStructure);
    const auto fill = [&](const TriangleMesh& m, const Eigen::Vector3i& t) {
        canvas.fill_polygon({m.vertices_m[t[0]].head<2>().cast<double>(),
                             m.vertices_m[t[1]].head<2>().cast<double>(),
                             m.vertices_m[t[2]].head<2>().cast<double>()},
                            colour);
    };
    // Every triangle of the wall and pillar boxes, projected.
    const TriangleMesh structure = sim::wall_and_pillar_mesh(scene);
    for (const auto& t : structure.triangles) fill(structure, t);
    // An environment mesh (a scan) has a floor and a ceiling too: only its standing faces between
    // 5 cm and 2 m, what a person would call its walls and obstacles.
    for (const sim::EnvironmentMesh& e : scene.environment) {
        if (!e.mesh_world) continue;
        const TriangleMesh& m = *e.mesh_world;
        for (const auto& t : m.triangles) {
            const Eigen::Vector3f a = m.vertices_m[t[0]], b = m.vertices_m[t[1]],
                                  c = m.vertices_m[t[2]];
            const Eigen::Vector3f n = (b - a).cross(c - a);
            const float lo = std::min({a.z(), b.z(), c.z()}), hi = std::max({a.z(), b.z(), c.z()});
            if (std::abs(n.z()) < 0.7f * n.norm() && hi > 0.05f && lo < 2.0f) fill(m, t);
        }
    }
}

void write_scene_png(const std::filesystem::path& path, const sim::Scene& scene,
                     const std::vector<sim::ObjectModel>& models, const ScenePicture& picture) {
    // Extra room above the floor for the title and legend.
    Canvas canvas(scene.floor_min_m, scene.floor_max_m + Eigen::Vector2d(0.0, 1.0),
                  picture.pixels_per_m, 0.3);
    const Eigen::Vector2d lo = scene.floor_min_m, hi = scene.floor_max_m;
    canvas.fill_polygon({lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}, {0.96, 0.96, 0.93});
    draw_structure(canvas, scene);
    for (std::size_t i = 0; i < scene.objects.size() && i < models.size(); ++i) {
        const sim::SceneObject& o = scene.objects[i];
        const Isometry2 T = to_isometry(o.pose);
        const Rgb colour = label_colour(to_semantic_label(o.cls));
        const TriangleMesh& m = models[i].mesh_object;
        for (const auto& t : m.triangles) {
            canvas.fill_polygon({T * m.vertices_m[t[0]].head<2>().cast<double>(),
                                 T * m.vertices_m[t[1]].head<2>().cast<double>(),
                                 T * m.vertices_m[t[2]].head<2>().cast<double>()},
                                colour, 0.25);
        }
        draw_box(canvas, models[i].box_object.transformed(lift_to_3d(o.pose)), colour);
    }
    for (const sim::ChairPusher& p : scene.pushers) {  // how far the chair is pulled out
        for (const sim::SceneObject& o : scene.objects) {
            if (o.id != p.chair_id) continue;
            const Eigen::Vector2d c(o.pose.x_m, o.pose.y_m);
            const Eigen::Vector2d back =
                -Eigen::Vector2d(std::cos(o.pose.yaw_rad), std::sin(o.pose.yaw_rad));
            canvas.stroke_polyline({c, c + p.pull_m * back}, label_colour(SemanticLabel::kPerson),
                                   3.0);
        }
    }
    for (const sim::Walker& w : scene.walkers) {
        canvas.stroke_polyline(w.route_m, label_colour(SemanticLabel::kPerson), 1.5, true, true);
        canvas.fill_circle(sim::walker_position_at(w, 0.0),
                           sim::kPersonRadius_m * picture.pixels_per_m,
                           label_colour(SemanticLabel::kPerson));
    }
    canvas.stroke_polyline(picture.route_m, {0.4, 0.4, 0.4}, 2.0, false, true);
    std::vector<Eigen::Vector2d> driven;
    for (const Pose2& p : picture.trajectory) driven.emplace_back(p.x_m, p.y_m);
    canvas.stroke_polyline(driven, {0.0, 0.0, 0.0}, 2.5);
    const struct {
        const Pose2& pose;
        Rgb colour;
        const char* name;
    } marks[] = {{scene.start, {0.1, 0.6, 0.1}, "start"},
                 {scene.waypoint, {0.1, 0.3, 0.9}, "waypoint"},
                 {scene.goal, {0.85, 0.1, 0.1}, "goal"}};
    for (const auto& m : marks) {
        const Eigen::Vector2d p(m.pose.x_m, m.pose.y_m);
        canvas.fill_circle(p, 7.0, m.colour);
        canvas.text(p + Eigen::Vector2d(0.25, 0.25), m.name, 13, m.colour);
    }
    canvas.scale_bar();
    canvas.text_px(10, 18, picture.title.empty() ? scene.name : picture.title, 14, {0, 0, 0});
    canvas.text_px(10, 36,
                   "orange: chairs  blue: tables  magenta: people  dashed: route  black: driven",
                   12, {0.2, 0.2, 0.2});
    canvas.save_png(path);
}

}  // namespace makeway::io
