#include "io/canvas.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace {

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

}  // namespace

struct Canvas::Impl {
    cairo_surface_t* surface = nullptr;
    cairo_t* cr = nullptr;
};

Canvas::Canvas(Eigen::Vector2d min_m, Eigen::Vector2d max_m, double pixels_per_m, double margin_m)
    : impl_(std::make_unique<Impl>()) {
    origin_m_ = min_m - Eigen::Vector2d::Constant(margin_m);
    const Eigen::Vector2d extent = max_m - min_m + Eigen::Vector2d::Constant(2 * margin_m);
    // Keep the whole extent inside the clamped image.
    ppm_ = std::min(
        {pixels_per_m, 4096.0 / std::max(extent.x(), 1e-3), 4096.0 / std::max(extent.y(), 1e-3)});
    width_ = std::clamp(static_cast<int>(std::ceil(extent.x() * ppm_)), 64, 4096);
    height_ = std::clamp(static_cast<int>(std::ceil(extent.y() * ppm_)), 64, 4096);
    impl_->surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
    impl_->cr = cairo_create(impl_->surface);
    cairo_set_source_rgb(impl_->cr, 1, 1, 1);
    cairo_paint(impl_->cr);
    cairo_set_line_join(impl_->cr, CAIRO_LINE_JOIN_ROUND);
    cairo_select_font_face(impl_->cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
}

Canvas::~Canvas() {
    cairo_destroy(impl_->cr);
    cairo_surface_destroy(impl_->surface);
}

#define MAKEWAY_PX(p) ((p).x() - origin_m_.x()) * ppm_, height_ - ((p).y() - origin_m_.y()) * ppm_

void Canvas::fill_polygon(const std::vector<Eigen::Vector2d>& pts, const Rgb& c, double alpha) {
    if (pts.size() < 3) return;
    cairo_t* cr = impl_->cr;
    cairo_move_to(cr, MAKEWAY_PX(pts[0]));
    for (std::size_t i = 1; i < pts.size(); ++i) cairo_line_to(cr, MAKEWAY_PX(pts[i]));
    cairo_close_path(cr);
    cairo_set_source_rgba(cr, c[0], c[1], c[2], alpha);
    cairo_fill(cr);
}

void Canvas::stroke_polyline(const std::vector<Eigen::Vector2d>& pts, const Rgb& c, double width_px,
                             bool closed, bool dashed) {
    if (pts.size() < 2) return;
    cairo_t* cr = impl_->cr;
    cairo_move_to(cr, MAKEWAY_PX(pts[0]));
    for (std::size_t i = 1; i < pts.size(); ++i) cairo_line_to(cr, MAKEWAY_PX(pts[i]));
    if (closed) cairo_close_path(cr);
    const double dash[] = {6.0, 4.0};
    cairo_set_dash(cr, dash, dashed ? 2 : 0, 0.0);
    cairo_set_line_width(cr, width_px);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_stroke(cr);
    cairo_set_dash(cr, dash, 0, 0.0);
}

void Canvas::cell(const Eigen::Vector2d& corner, double size, const Rgb& c) {
    cairo_t* cr = impl_->cr;
    const double x = (corner.x() - origin_m_.x()) * ppm_,
                 y = height_ - (corner.y() + size - origin_m_.y()) * ppm_;
    cairo_rectangle(cr, x, y, size * ppm_ + 0.5, size * ppm_ + 0.5);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_fill(cr);
}

void Canvas::fill_circle(const Eigen::Vector2d& centre, double radius_px, const Rgb& c) {
    cairo_t* cr = impl_->cr;
    cairo_new_sub_path(cr);
    cairo_arc(cr, MAKEWAY_PX(centre), radius_px, 0, 2 * M_PI);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_fill(cr);
}

void Canvas::dot(const Eigen::Vector2d& p, double size_px, const Rgb& c) {
    cairo_t* cr = impl_->cr;
    const double x = (p.x() - origin_m_.x()) * ppm_, y = height_ - (p.y() - origin_m_.y()) * ppm_;
    cairo_rectangle(cr, x - size_px / 2, y - size_px / 2, size_px, size_px);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_fill(cr);
}

void Canvas::text(const Eigen::Vector2d& p, const std::string& s, double size_px, const Rgb& c) {
    text_px((p.x() - origin_m_.x()) * ppm_, height_ - (p.y() - origin_m_.y()) * ppm_, s, size_px,
            c);
}

void Canvas::text_px(double x_px, double y_px, const std::string& s, double size_px, const Rgb& c) {
    cairo_t* cr = impl_->cr;
    cairo_set_font_size(cr, size_px);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, x_px, y_px);
    cairo_show_text(cr, s.c_str());
}

void Canvas::scale_bar() {
    cairo_t* cr = impl_->cr;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 2.0);
    cairo_move_to(cr, 10, height_ - 10);
    cairo_line_to(cr, 10 + ppm_, height_ - 10);
    cairo_stroke(cr);
    text_px(10, height_ - 16, "1 m", 12, {0, 0, 0});
}

#undef MAKEWAY_PX

void Canvas::save_png(const std::filesystem::path& path) {
    std::string png;
    cairo_surface_flush(impl_->surface);
    const cairo_status_t status =
        cairo_surface_write_to_png_stream(impl_->surface, append_to_string, &png);
    if (status != CAIRO_STATUS_SUCCESS) {
        throw FileError(path.string(),
                        std::string("PNG encoding failed: ") + cairo_status_to_string(status));
    }
    write_file_atomic(path, png);
}

void write_contact_sheet(const std::filesystem::path& path,
                         const std::vector<std::filesystem::path>& pngs,
                         const std::vector<std::string>& captions, int columns, int thumb_px) {
    constexpr int kCaption_px = 18;
    columns = std::max(
        1, std::min<int>(columns, static_cast<int>(std::max<std::size_t>(pngs.size(), 1))));
    const int rows = static_cast<int>((pngs.size() + columns - 1) / columns);
    // Square cells; each picture scaled to fit its cell, keeping its aspect ratio.
    const int thumb_h = thumb_px;
    std::vector<cairo_surface_t*> images;
    const auto release = [&images] {
        for (cairo_surface_t* i : images) cairo_surface_destroy(i);
    };
    for (const auto& p : pngs) {
        cairo_surface_t* img = cairo_image_surface_create_from_png(p.c_str());
        if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
            cairo_surface_destroy(img);
            release();
            throw FileError(p.string(), "not a readable PNG");
        }
        images.push_back(img);
    }
    const int width = columns * thumb_px, height = std::max(1, rows) * (thumb_h + kCaption_px);
    cairo_surface_t* sheet = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t* cr = cairo_create(sheet);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12);
    for (std::size_t i = 0; i < images.size(); ++i) {
        const int x = static_cast<int>(i % columns) * thumb_px,
                  y = static_cast<int>(i / columns) * (thumb_h + kCaption_px);
        const double scale =
            std::min(static_cast<double>(thumb_px) / cairo_image_surface_get_width(images[i]),
                     static_cast<double>(thumb_h) / cairo_image_surface_get_height(images[i]));
        cairo_save(cr);
        cairo_translate(cr, x + 0.5 * (thumb_px - scale * cairo_image_surface_get_width(images[i])),
                        y + 0.5 * (thumb_h - scale * cairo_image_surface_get_height(images[i])));
        cairo_scale(cr, scale, scale);
        cairo_set_source_surface(cr, images[i], 0, 0);
        cairo_paint(cr);
        cairo_restore(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, x + 4, y + thumb_h + kCaption_px - 5);
        cairo_show_text(cr, i < captions.size() ? captions[i].c_str() : "");
    }
    release();
    cairo_destroy(cr);
    std::string png;
    cairo_surface_flush(sheet);
    const cairo_status_t status = cairo_surface_write_to_png_stream(sheet, append_to_string, &png);
    cairo_surface_destroy(sheet);
    if (status != CAIRO_STATUS_SUCCESS)
        throw FileError(path.string(),
                        std::string("PNG encoding failed: ") + cairo_status_to_string(status));
    write_file_atomic(path, png);
}

}  // namespace makeway::io
