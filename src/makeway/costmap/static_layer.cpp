#include "makeway/costmap/static_layer.hpp"

#include <cmath>

namespace makeway::costmap {

void fill_rectangle(Costmap& grid, const Eigen::Vector2d& centre, const Eigen::Vector2d& size,
                    double yaw, std::uint8_t value) {
    const double c = std::cos(yaw), s = std::sin(yaw);
    const Eigen::Vector2d h = 0.5 * size;
    const Eigen::Vector2d r(std::abs(c) * h.x() + std::abs(s) * h.y(),
                            std::abs(s) * h.x() + std::abs(c) * h.y());
    const GridWindow w = grid.window_of(centre - r, centre + r);
    for (int y = w.y0; y < w.y1; ++y) {
        for (int x = w.x0; x < w.x1; ++x) {
            const Eigen::Vector2d d = grid.centre_of(x, y) - centre;
            const double lx = c * d.x() + s * d.y(), ly = -s * d.x() + c * d.y();
            // A cell is occupied when its centre is within half a cell of the rectangle.
            const double tol = 0.5 * grid.resolution_m;
            if (std::abs(lx) <= h.x() + tol && std::abs(ly) <= h.y() + tol) grid.at(x, y) = value;
        }
    }
}

void StaticLayer::update_bounds(const Costmap& master, const LayerInput&, GridWindow& window) {
    if (!written_) window.expand({0, 0, master.width, master.height});
}

void StaticLayer::update_costs(Costmap& master, const GridWindow& window) {
    // Rewritten inside every window: the master is reset there before the layers write.
    written_ = true;
    for (int y = window.y0; y < window.y1; ++y) {
        for (int x = window.x0; x < window.x1; ++x) {
            const std::uint8_t v = map_.at(x, y);
            std::uint8_t& m = master.at(x, y);
            if (v == cost::kUnknown) {
                if (m == cost::kFree) m = cost::kUnknown;  // unknown ranks below every known cost
            } else if (v > m || m == cost::kUnknown) {
                m = std::max(v, m == cost::kUnknown ? cost::kFree : m);
            }
        }
    }
}

}  // namespace makeway::costmap
