#include "io/top_down_png.hpp"

#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace {

using Rgb = std::array<double, 3>;

Rgb label_colour(std::uint8_t label) {
    switch (static_cast<SemanticLabel>(label)) {
        case SemanticLabel::kGround: return {0.75, 0.75, 0.75};
        case SemanticLabel::kStructure: return {0.25, 0.25, 0.25};
        case SemanticLabel::kChair: return {0.85, 0.35, 0.10};
        case SemanticLabel::kTable: return {0.10, 0.45, 0.80};
        case SemanticLabel::kPerson: return {0.80, 0.10, 0.60};
        default: return {0.45, 0.60, 0.30};
    }
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

}  // namespace

void write_top_down_png(const std::filesystem::path& path, const PointCloud& cloud,
                        const std::vector<LabelledBox>& boxes, const TopDownStyle& style) {
    PointBounds b = compute_bounds(cloud);
    for (const auto& lb : boxes) {
        for (const auto& c : lb.box.bev_corners()) {
            const Eigen::Vector3f p(static_cast<float>(c.x()), static_cast<float>(c.y()), 0.0f);
            b.min_m = b.valid ? b.min_m.cwiseMin(p) : p;
            b.max_m = b.valid ? b.max_m.cwiseMax(p) : p;
            b.valid = true;
        }
    }
    if (!b.valid) b.max_m = Eigen::Vector3f::Ones();
    const double x0 = b.min_m.x() - style.margin_m, y0 = b.min_m.y() - style.margin_m;
    const double ppm = style.pixels_per_m;
    const int width = std::clamp(static_cast<int>((b.max_m.x() - x0 + style.margin_m) * ppm), 64, 4096);
    const int height = std::clamp(static_cast<int>((b.max_m.y() - y0 + style.margin_m) * ppm), 64, 4096);
    auto px = [&](double x) { return (x - x0) * ppm; };
    auto py = [&](double y) { return height - (y - y0) * ppm; };  // y up

    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);

    const float z_lo = b.min_m.z(), z_span = std::max(1e-3f, b.max_m.z() - b.min_m.z());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto& p = cloud.xyz[i];
        if (!p.allFinite()) continue;
        Rgb c = cloud.label.empty() ? Rgb{0.2, 0.2, 0.3 + 0.7 * (p.z() - z_lo) / z_span}
                                    : label_colour(cloud.label[i]);
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_rectangle(cr, px(p.x()) - 1, py(p.y()) - 1, 2, 2);
        cairo_fill(cr);
    }
    cairo_set_line_width(cr, 2.0);
    for (const auto& lb : boxes) {
        const auto corners = lb.box.bev_corners();
        const Rgb c = label_colour(static_cast<std::uint8_t>(lb.label));
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_move_to(cr, px(corners[0].x()), py(corners[0].y()));
        for (int k = 1; k < 4; ++k) cairo_line_to(cr, px(corners[k].x()), py(corners[k].y()));
        cairo_close_path(cr);
        cairo_stroke(cr);
        // Heading: a line from the centre to the middle of the front (+x) face.
        const Eigen::Vector2d front = 0.5 * (corners[1] + corners[2]);
        cairo_move_to(cr, px(lb.box.centre_m.x()), py(lb.box.centre_m.y()));
        cairo_line_to(cr, px(front.x()), py(front.y()));
        cairo_stroke(cr);
    }
    // Scale bar: 1 m.
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, 10, height - 10);
    cairo_line_to(cr, 10 + ppm, height - 10);
    cairo_stroke(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12);
    cairo_move_to(cr, 10, height - 16);
    cairo_show_text(cr, "1 m");
    if (!style.title.empty()) {
        cairo_move_to(cr, 10, 18);
        cairo_show_text(cr, style.title.c_str());
    }
    cairo_destroy(cr);
    std::string png;
    const cairo_status_t status = cairo_surface_write_to_png_stream(surface, append_to_string, &png);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS) {
        throw FileError(path.string(), std::string("PNG encoding failed: ") +
                                           cairo_status_to_string(status));
    }
    write_file_atomic(path, png);
}

}  // namespace makeway::io
