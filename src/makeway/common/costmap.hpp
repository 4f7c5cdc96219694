#pragma once
// A 2D cost grid in the world frame, with the ROS/nav2 cost values. The value type the costmap
// stage produces and the planners read.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace makeway {

namespace cost {
constexpr std::uint8_t kFree = 0;
constexpr std::uint8_t kMaxSoft = 252;    ///< highest cost a planner may still drive through
constexpr std::uint8_t kInscribed = 253;  ///< the robot's centre here puts its body on an obstacle
constexpr std::uint8_t kLethal = 254;     ///< an obstacle
constexpr std::uint8_t kUnknown = 255;
}  // namespace cost

/// Half-open cell rectangle [x0, x1) x [y0, y1).
struct GridWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    void expand(const GridWindow& o) {
        if (o.empty()) return;
        if (empty()) {
            *this = o;
            return;
        }
        x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0), x1 = std::max(x1, o.x1),
        y1 = std::max(y1, o.y1);
    }
    GridWindow grown(int cells) const {
        return empty() ? *this : GridWindow{x0 - cells, y0 - cells, x1 + cells, y1 + cells};
    }
    GridWindow clipped(int width, int height) const {
        return {std::max(x0, 0), std::max(y0, 0), std::min(x1, width), std::min(y1, height)};
    }
};

struct Costmap {
    Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< world position of cell (0, 0)'s corner
    double resolution_m = 0.05;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> cost;  ///< row-major

    Costmap() = default;
    Costmap(Eigen::Vector2d origin, double resolution, int w, int h,
            std::uint8_t fill = cost::kFree)
        : origin_m(origin),
          resolution_m(resolution),
          width(w),
          height(h),
          cost(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}

    bool inside(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
    std::uint8_t at(int ix, int iy) const {
        return cost[static_cast<std::size_t>(iy) * width + ix];
    }
    std::uint8_t& at(int ix, int iy) { return cost[static_cast<std::size_t>(iy) * width + ix]; }
    Eigen::Vector2i cell_of(const Eigen::Vector2d& p_m) const {
        const Eigen::Vector2d q = (p_m - origin_m) / resolution_m;
        return {static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))};
    }
    Eigen::Vector2d centre_of(int ix, int iy) const {
        return origin_m + resolution_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
    }
    /// Cost at a world point; nullopt outside the grid.
    std::optional<std::uint8_t> cost_at(const Eigen::Vector2d& p_m) const {
        const Eigen::Vector2i c = cell_of(p_m);
        if (!inside(c.x(), c.y())) return std::nullopt;
        return at(c.x(), c.y());
    }
    /// Cells covering a world rectangle, clipped to the grid.
    GridWindow window_of(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m) const {
        const Eigen::Vector2i a = cell_of(min_m), b = cell_of(max_m);
        return GridWindow{a.x(), a.y(), b.x() + 1, b.y() + 1}.clipped(width, height);
    }
};

}  // namespace makeway
