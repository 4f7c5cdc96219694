#pragma once
// A small top-down drawing surface over cairo: world coordinates in metres (x right, y up), PNG
// output written atomically. Every picture makeway draws goes through it.
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace makeway::io {

using Rgb = std::array<double, 3>;

class Canvas {
  public:
    /// Covers [min_m, max_m] plus margin_m at pixels_per_m (the image is clamped to 64..4096 px).
    Canvas(Eigen::Vector2d min_m, Eigen::Vector2d max_m, double pixels_per_m,
           double margin_m = 0.5);
    ~Canvas();
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    void fill_polygon(const std::vector<Eigen::Vector2d>& points_m, const Rgb& colour,
                      double alpha = 1.0);
    void stroke_polyline(const std::vector<Eigen::Vector2d>& points_m, const Rgb& colour,
                         double width_px, bool closed = false, bool dashed = false);
    void fill_circle(const Eigen::Vector2d& centre_m, double radius_px, const Rgb& colour);
    void dot(const Eigen::Vector2d& p_m, double size_px, const Rgb& colour);
    void text(const Eigen::Vector2d& p_m, const std::string& s, double size_px, const Rgb& colour);
    /// Text at a pixel position (titles, legends).
    void text_px(double x_px, double y_px, const std::string& s, double size_px, const Rgb& colour);
    /// Paints a grid (origin = corner of cell (0, 0), row-major); colour(i) returns nullopt to
    /// skip.
    template <typename ColourFn>
    void grid(const Eigen::Vector2d& origin_m, double resolution_m, int width, int height,
              ColourFn colour) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                if (const auto c = colour(x, y))
                    cell(origin_m + resolution_m * Eigen::Vector2d(x, y), resolution_m, *c);
            }
        }
    }
    /// One filled square cell whose lower-left corner is corner_m.
    void cell(const Eigen::Vector2d& corner_m, double size_m, const Rgb& colour);
    /// A 1 m scale bar in the bottom-left corner.
    void scale_bar();

    int width_px() const { return width_; }
    int height_px() const { return height_; }
    /// Encodes PNG and writes it atomically; throws FileError.
    void save_png(const std::filesystem::path& path);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    Eigen::Vector2d origin_m_;
    double ppm_;
    int width_ = 0;
    int height_ = 0;
};

/// Thumbnails of `pngs` (each scaled into a thumb_px square, aspect kept; rows of `columns`) with a
/// caption under each, as one PNG: a drive's keyframes at a glance. Throws FileError naming an
/// unreadable input or the output.
void write_contact_sheet(const std::filesystem::path& path,
                         const std::vector<std::filesystem::path>& pngs,
                         const std::vector<std::string>& captions, int columns = 6,
                         int thumb_px = 320);

}  // namespace makeway::io
