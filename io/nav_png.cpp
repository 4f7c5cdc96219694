#include "io/nav_png.hpp"

#include <cmath>

#include "io/canvas.hpp"
#include "io/scene_png.hpp"
#include "io/top_down_png.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::io {
namespace {

const Rgb kPathColours[] = {{0.0, 0.0, 0.0}, {0.1, 0.5, 0.1}, {0.55, 0.1, 0.75}, {0.0, 0.45, 0.7}};

}  // namespace

std::optional<Rgb> cost_colour(std::uint8_t c) {
    if (c == cost::kFree) return std::nullopt;
    if (c == cost::kLethal) return Rgb{0.1, 0.1, 0.1};
    if (c == cost::kInscribed) return Rgb{0.55, 0.55, 0.55};
    if (c == cost::kUnknown) return Rgb{0.75, 0.8, 0.9};
    const double f = c / 252.0;  // soft: pale yellow to red
    return Rgb{1.0, 0.95 - 0.75 * f, 0.7 - 0.7 * f};
}

void write_nav_png(const std::filesystem::path& path, const sim::Scene& scene,
                   const Costmap& costmap, const std::vector<DrivenPath>& paths,
                   const std::vector<Eigen::Vector2d>& plan, const std::string& title,
                   const costmap::AffordanceParams& zones) {
    Canvas canvas(scene.floor_min_m, scene.floor_max_m + Eigen::Vector2d(0.0, 1.0), 40.0, 0.3);
    canvas.grid(costmap.origin_m, costmap.resolution_m, costmap.width, costmap.height,
                [&](int x, int y) { return cost_colour(costmap.at(x, y)); });
    if (costmap.cost.empty())
        draw_structure(canvas, scene);  // no costmap: draw the building itself
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    for (const sim::ObjectState& s : sim::object_states_at(scene, models, 0.0)) {
        ObjectEstimate o;
        o.cls = s.cls;
        o.box_world = s.box_world;
        const Rgb colour = label_colour(to_semantic_label(s.cls));
        canvas.stroke_polyline(costmap::zone_outline(o, zones), colour, 1.0, true, true);
        draw_box(canvas, s.box_world, colour);
    }
    canvas.stroke_polyline(plan, {0.4, 0.4, 0.4}, 1.5, false, true);
    double legend_y = 36;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const Rgb colour = kPathColours[i % 4];
        std::vector<Eigen::Vector2d> pts;
        for (const Pose2& p : paths[i].poses) pts.emplace_back(p.x_m, p.y_m);
        canvas.stroke_polyline(pts, colour, 2.5);
        canvas.text_px(10, legend_y, paths[i].label, 12, colour);
        legend_y += 15;
    }
    for (const auto& [pose, colour] :
         {std::pair{scene.start, Rgb{0.1, 0.6, 0.1}}, std::pair{scene.waypoint, Rgb{0.1, 0.3, 0.9}},
          std::pair{scene.goal, Rgb{0.85, 0.1, 0.1}}}) {
        canvas.fill_circle({pose.x_m, pose.y_m}, 7.0, colour);
    }
    canvas.scale_bar();
    canvas.text_px(10, 18, title, 14, {0, 0, 0});
    canvas.save_png(path);
}

void write_map_png(const std::filesystem::path& path, const Costmap& costmap,
                   const std::vector<ObjectEstimate>& objects,
                   const costmap::AffordanceParams& zones, const std::vector<Pose2>& trajectory,
                   const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
                   const std::string& title) {
    Canvas canvas(min_m, max_m + Eigen::Vector2d(0.0, 0.8), 40.0, 0.3);
    // Only the cells in view: a run's costmap may be much larger than the area driven.
    const Eigen::Vector2i lo = costmap.cell_of(min_m).cwiseMax(Eigen::Vector2i::Zero());
    const Eigen::Vector2i hi = (costmap.cell_of(max_m) + Eigen::Vector2i::Ones())
                                   .cwiseMin(Eigen::Vector2i(costmap.width, costmap.height));
    if ((hi - lo).minCoeff() > 0) {
        canvas.grid(costmap.centre_of(lo.x(), lo.y()) -
                        Eigen::Vector2d::Constant(0.5 * costmap.resolution_m),
                    costmap.resolution_m, hi.x() - lo.x(), hi.y() - lo.y(),
                    [&](int x, int y) { return cost_colour(costmap.at(lo.x() + x, lo.y() + y)); });
    }
    for (const ObjectEstimate& o : objects) {
        const Rgb colour = label_colour(to_semantic_label(o.cls));
        if (o.existence >= zones.min_existence)
            canvas.stroke_polyline(costmap::zone_outline(o, zones), colour, 1.0, true, true);
        draw_box(canvas, o.box_world, colour);
        canvas.text(o.box_world.centre_m.head<2>(), std::to_string(o.id), 10, {0, 0, 0});
    }
    std::vector<Eigen::Vector2d> pts;
    for (const Pose2& p : trajectory) pts.emplace_back(p.x_m, p.y_m);
    canvas.stroke_polyline(pts, kPathColours[0], 2.0);
    if (!trajectory.empty()) canvas.fill_circle(pts.back(), 5.0, {0.85, 0.1, 0.1});
    canvas.scale_bar();
    canvas.text_px(10, 18, title, 14, {0, 0, 0});
    canvas.save_png(path);
}

}  // namespace makeway::io
