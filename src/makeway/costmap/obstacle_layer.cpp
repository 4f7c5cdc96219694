#include "makeway/costmap/obstacle_layer.hpp"

#include <cmath>
#include <cstdlib>

namespace makeway::costmap {

std::vector<std::string> ObstacleLayerParams::validate() const {
    std::vector<std::string> out;
    if (!(body.ground_clearance_m >= 0.0 && body.ground_clearance_m < body.top_m)) out.push_back("the body's ground clearance must be in [0, its top)");
    if (!(low_band_top_m >= 0.0 && low_mark_range_m >= 0.0)) out.push_back("low_band_top_m and low_mark_range_m must be >= 0");
    if (low_min_returns < 1 || low_min_returns > 65535) out.push_back("low_min_returns must be in [1, 65535]");
    if (!(low_min_share >= 0.0 && low_min_share <= 1.0)) out.push_back("low_min_share must be in [0, 1]");
    if (!(mark_range_m > 0.0 && mark_range_m <= clear_range_m)) out.push_back("mark_range_m must be in (0, clear_range_m]");
    if (!(clear_range_m > 0.0 && clear_range_m <= 100.0)) out.push_back("clear_range_m must be in (0, 100]");
    return out;
}

ObstacleLayer::ObstacleLayer(const Costmap& geometry, const ObstacleLayerParams& params)
    : params_(params), grid_(geometry.origin_m, geometry.resolution_m, geometry.width, geometry.height) {}

void ObstacleLayer::update_bounds(const Costmap&, const LayerInput& input, GridWindow& window) {
    if (!input.points_world) return;
    const Eigen::Vector2i s = grid_.cell_of(input.sensor_world_m.head<2>());
    // Unique endpoint cells: one ray per cell is enough to clear and mark (the cell's lowest
    // return, which clears the most). The per-cell marks are kept between updates (zeroed cell by
    // cell at the end) instead of a grid-sized allocation per sweep.
    std::vector<std::uint8_t>& endpoint = endpoint_;
    endpoint.resize(grid_.cost.size(), 0);
    low_.resize(grid_.cost.size(), 0);
    floor_.resize(grid_.cost.size(), 0);
    low_top_.resize(grid_.cost.size(), 0.0f);
    top_.resize(grid_.cost.size(), 0.0f);
    end_z_.resize(grid_.cost.size(), 0.0f);
    std::vector<int>& cells = cells_;
    cells.clear();
    const double mark2 = params_.mark_range_m * params_.mark_range_m;
    const double clear2 = params_.clear_range_m * params_.clear_range_m;
    const double low2 = params_.low_mark_range_m * params_.low_mark_range_m;
    for (const Eigen::Vector3f& p : input.points_world->xyz) {
        if (!p.allFinite() || p.z() > params_.body.top_m) continue;
        const double d2 = (p.head<2>().cast<double>() - input.sensor_world_m.head<2>()).squaredNorm();
        if (d2 > clear2) continue;
        const Eigen::Vector2i c = grid_.cell_of(p.head<2>().cast<double>());
        if (!grid_.inside(c.x(), c.y())) continue;
        const int idx = c.y() * grid_.width + c.x();
        if (endpoint[idx] == 0) {
            cells.push_back(idx);
            end_z_[idx] = p.z();
            endpoint[idx] = 1;
        }
        end_z_[idx] = std::min(end_z_[idx], p.z());
        if (!params_.body.can_hit(p.z()) || d2 > mark2) {
            if (p.z() < params_.low_band_top_m && floor_[idx] < 65535) ++floor_[idx];
            continue;
        }
        if (p.z() >= params_.low_band_top_m) {
            top_[idx] = endpoint[idx] == 2 ? std::max(top_[idx], p.z()) : p.z();
            endpoint[idx] = 2;
        } else if (d2 <= low2 && low_[idx] < 65535) {
            ++low_[idx];
            low_top_[idx] = low_[idx] == 1 ? p.z() : std::max(low_top_[idx], p.z());
        }
    }
    // Low returns mark a cell when enough of them, and a large enough share of the cell's returns
    // below the low band's top, stand above the clearance (floor noise lifts a few, not a share).
    for (int idx : cells) {
        if (endpoint[idx] != 2 && low_[idx] >= params_.low_min_returns &&
            low_[idx] >= params_.low_min_share * (low_[idx] + floor_[idx])) {
            endpoint[idx] = 2;
            top_[idx] = low_top_[idx];
        }
    }
    GridWindow touched{s.x(), s.y(), s.x() + 1, s.y() + 1};
    const double sensor_z = input.sensor_world_m.z();
    // Clear along each ray (Bresenham), stopping before the endpoint cell; a low mark only where
    // the ray passes no higher than its top (plus a noise margin).
    for (int idx : cells) {
        const int ex = idx % grid_.width, ey = idx / grid_.width;
        touched.expand({ex, ey, ex + 1, ey + 1});
        const double length = std::hypot(ex - s.x(), ey - s.y());
        int x = s.x(), y = s.y();
        const int dx = std::abs(ex - x), dy = -std::abs(ey - y), sx = x < ex ? 1 : -1, sy = y < ey ? 1 : -1;
        int err = dx + dy;
        while (x != ex || y != ey) {
            if (grid_.inside(x, y)) {
                const int i = y * grid_.width + x;
                if (endpoint[i] != 2 && grid_.cost[i] != cost::kFree) {
                    bool clears = top_[i] >= params_.low_band_top_m;  // tall marks: any ray (sparse rings rarely see their top)
                    if (!clears) {
                        const double f = length > 0.0 ? std::hypot(x - s.x(), y - s.y()) / length : 0.0;
                        clears = sensor_z + f * (end_z_[idx] - sensor_z) <= top_[i] + kClearMargin_m;
                    }
                    if (clears) grid_.cost[i] = cost::kFree;
                }
            }
            const int e2 = 2 * err;
            if (e2 >= dy) err += dy, x += sx;
            if (e2 <= dx) err += dx, y += sy;
        }
    }
    for (int idx : cells) {
        if (endpoint[idx] == 2) grid_.cost[idx] = cost::kLethal;
        endpoint[idx] = 0;
        low_[idx] = floor_[idx] = 0;
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
