#include "makeway/costmap/obstacle_layer.hpp"

#include <cmath>
#include <cstdlib>

namespace makeway::costmap {

std::vector<std::string> ObstacleLayerParams::validate() const {
    std::vector<std::string> out;
    if (!(min_height_m < max_height_m)) out.push_back("min_height_m must be below max_height_m");
    if (!(mark_range_m > 0.0 && mark_range_m <= clear_range_m)) out.push_back("mark_range_m must be in (0, clear_range_m]");
    if (!(clear_range_m > 0.0 && clear_range_m <= 100.0)) out.push_back("clear_range_m must be in (0, 100]");
    return out;
}

ObstacleLayer::ObstacleLayer(const Costmap& geometry, const ObstacleLayerParams& params)
    : params_(params), grid_(geometry.origin_m, geometry.resolution_m, geometry.width, geometry.height) {}

void ObstacleLayer::update_bounds(const Costmap&, const LayerInput& input, GridWindow& window) {
    if (!input.points_world) return;
    const Eigen::Vector2i s = grid_.cell_of(input.sensor_world_m.head<2>());
    // Unique endpoint cells: one ray per cell is enough to clear and mark. The per-cell marks are
    // kept between updates (zeroed cell by cell at the end) instead of a grid-sized allocation
    // per sweep.
    std::vector<std::uint8_t>& endpoint = endpoint_;
    endpoint.resize(grid_.cost.size(), 0);
    std::vector<int>& cells = cells_;
    cells.clear();
    const double mark2 = params_.mark_range_m * params_.mark_range_m;
    const double clear2 = params_.clear_range_m * params_.clear_range_m;
    for (const Eigen::Vector3f& p : input.points_world->xyz) {
        if (!p.allFinite() || p.z() > params_.max_height_m) continue;
        const double d2 = (p.head<2>().cast<double>() - input.sensor_world_m.head<2>()).squaredNorm();
        if (d2 > clear2) continue;
        const Eigen::Vector2i c = grid_.cell_of(p.head<2>().cast<double>());
        if (!grid_.inside(c.x(), c.y())) continue;
        const int idx = c.y() * grid_.width + c.x();
        const std::uint8_t kind = (p.z() >= params_.min_height_m && d2 <= mark2) ? 2 : 1;
        if (endpoint[idx] == 0) cells.push_back(idx);
        endpoint[idx] = std::max(endpoint[idx], kind);
    }
    GridWindow touched{s.x(), s.y(), s.x() + 1, s.y() + 1};
    // Clear along each ray (Bresenham), stopping before the endpoint cell.
    for (int idx : cells) {
        const int ex = idx % grid_.width, ey = idx / grid_.width;
        touched.expand({ex, ey, ex + 1, ey + 1});
        int x = s.x(), y = s.y();
        const int dx = std::abs(ex - x), dy = -std::abs(ey - y), sx = x < ex ? 1 : -1, sy = y < ey ? 1 : -1;
        int err = dx + dy;
        while (x != ex || y != ey) {
            if (grid_.inside(x, y) && endpoint[y * grid_.width + x] != 2) grid_.at(x, y) = cost::kFree;
            const int e2 = 2 * err;
            if (e2 >= dy) err += dy, x += sx;
            if (e2 <= dx) err += dx, y += sy;
        }
    }
    for (int idx : cells) {
        if (endpoint[idx] == 2) grid_.cost[idx] = cost::kLethal;
        endpoint[idx] = 0;
    }
    window.expand(touched.clipped(grid_.width, grid_.height));
}

void ObstacleLayer::update_costs(Costmap& master, const GridWindow& window) {
    for (int y = window.y0; y < window.y1; ++y) {
        for (int x = window.x0; x < window.x1; ++x) {
            const std::uint8_t v = grid_.at(x, y);
            std::uint8_t& m = master.at(x, y);
            if (v != cost::kFree && (v > m || m == cost::kUnknown)) m = v;
        }
    }
}

}  // namespace makeway::costmap
