#include "io/top_down_png.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/canvas.hpp"

namespace makeway::io {

Rgb label_colour(SemanticLabel label) {
    switch (label) {
        case SemanticLabel::kGround:
            return {0.80, 0.80, 0.80};
        case SemanticLabel::kCeiling:
            return {0.90, 0.85, 0.70};
        case SemanticLabel::kStructure:
            return {0.25, 0.25, 0.25};
        case SemanticLabel::kChair:
            return {0.85, 0.35, 0.10};
        case SemanticLabel::kTable:
            return {0.10, 0.45, 0.80};
        case SemanticLabel::kPerson:
            return {0.80, 0.10, 0.60};
        default:
            return {0.45, 0.60, 0.30};
    }
}

void draw_box(Canvas& canvas, const OrientedBox& box, const Rgb& colour) {
    const auto c = box.bev_corners();
    canvas.stroke_polyline({c.begin(), c.end()}, colour, 2.0, true);
    // Heading: from the centre to the middle of the front (+x) face.
    canvas.stroke_polyline({box.centre_m.head<2>(), 0.5 * (c[1] + c[2])}, colour, 2.0);
}

void write_top_down_png(const std::filesystem::path& path, const PointCloud& cloud,
                        const std::vector<ObjectEstimate>& objects, const TopDownStyle& style) {
    PointBounds b = compute_bounds(cloud);
    Eigen::Vector2d lo =
        b.valid ? Eigen::Vector2d(b.min_m.head<2>().cast<double>()) : Eigen::Vector2d(0, 0);
    Eigen::Vector2d hi =
        b.valid ? Eigen::Vector2d(b.max_m.head<2>().cast<double>()) : Eigen::Vector2d(1, 1);
    for (const auto& o : objects) {
        for (const auto& c : o.box_world.bev_corners()) {
            lo = lo.cwiseMin(c);
            hi = hi.cwiseMax(c);
        }
    }
    Canvas canvas(lo, hi, style.pixels_per_m, style.margin_m);
    const float z_lo = b.min_m.z(), z_span = std::max(1e-3f, b.max_m.z() - b.min_m.z());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto& p = cloud.xyz[i];
        if (!p.allFinite()) continue;
        const Rgb c = cloud.label.empty()
                          ? Rgb{0.2, 0.2, 0.3 + 0.7 * (p.z() - z_lo) / z_span}
                          : label_colour(static_cast<SemanticLabel>(cloud.label[i]));
        canvas.dot(p.head<2>().cast<double>(), 2.0, c);
    }
    for (const auto& o : objects)
        draw_box(canvas, o.box_world, label_colour(to_semantic_label(o.cls)));
    canvas.scale_bar();
    if (!style.title.empty()) canvas.text_px(10, 18, style.title, 12, {0, 0, 0});
    canvas.save_png(path);
}

void write_detections_png(const std::filesystem::path& path, const PointCloud& raw,
                          const PointCloud& kept, const std::vector<Detection>& detections,
                          double reach_m, const std::string& title) {
    const auto within = [reach_m](const Eigen::Vector3f& p) {
        return p.allFinite() && std::abs(p.x()) <= reach_m && std::abs(p.y()) <= reach_m;
    };
    // The picture covers what was seen within reach, and every box.
    Eigen::Vector2d lo(0, 0), hi(0, 0);
    for (const auto& p : raw.xyz) {
        if (!within(p)) continue;
        lo = lo.cwiseMin(p.head<2>().cast<double>());
        hi = hi.cwiseMax(p.head<2>().cast<double>());
    }
    for (const Detection& d : detections) {
        for (const auto& c : d.box_sensor.bev_corners()) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    }
    const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1.0});
    Canvas canvas(lo, hi, std::clamp(1600.0 / span, 10.0, 60.0), 1.0);
    for (const auto& p : raw.xyz) {
        if (within(p)) canvas.dot(p.head<2>().cast<double>(), 1.5, {0.82, 0.82, 0.82});
    }
    float z_lo = 0.0f, z_hi = 0.0f;
    bool any = false;
    for (const auto& p : kept.xyz) {
        if (!within(p)) continue;
        z_lo = any ? std::min(z_lo, p.z()) : p.z(), z_hi = any ? std::max(z_hi, p.z()) : p.z();
        any = true;
    }
    const float z_span = std::max(1e-3f, z_hi - z_lo);
    for (const auto& p : kept.xyz) {
        if (!within(p)) continue;
        const double t = (p.z() - z_lo) / z_span;
        canvas.dot(p.head<2>().cast<double>(), 2.0, {0.15, 0.15 + 0.35 * t, 0.35 + 0.6 * t});
    }
    for (const Detection& d : detections) {
        const Rgb colour = label_colour(to_semantic_label(d.cls));
        draw_box(canvas, d.box_sensor, colour);
        char caption[64];
        std::snprintf(caption, sizeof(caption), "%s %.2f", std::string(to_string(d.cls)).c_str(),
                      d.score);
        const auto c = d.box_sensor.bev_corners();
        Eigen::Vector2d at = c[0];
        for (const auto& corner : c) at = at.cwiseMax(corner);  // beside the box's upper right
        canvas.text(at, caption, 11, colour);
    }
    canvas.fill_circle({0.0, 0.0}, 5.0, {0.0, 0.0, 0.0});  // the sensor
    canvas.scale_bar();
    if (!title.empty()) canvas.text_px(10, 18, title, 12, {0, 0, 0});
    canvas.save_png(path);
}

}  // namespace makeway::io
