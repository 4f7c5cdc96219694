#include "makeway/costmap/obstacle_layer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdlib>

#include "makeway/common/floor_index.hpp"
#include "makeway/common/handover.hpp"
#include "makeway/costmap/param_tables.hpp"
#include "makeway/costmap/ray_walk.hpp"

namespace makeway::costmap {

namespace {

// Fewer endpoint cells than this stay on the caller's thread (a parallel loop's start costs more).
constexpr std::size_t kParallelRays = 1024;

}  // namespace

struct ObstacleLayer::Threads {
    explicit Threads(int n) : arena(n) {}
    tbb::task_arena arena;  ///< thread-safe: copies of the layer may share it
};

std::vector<std::string> ObstacleLayerParams::validate() const {
    std::vector<std::string> out = obstacle_layer_table().problems(*this);
    if (!(body.ground_clearance_m >= 0.0 && body.ground_clearance_m < body.top_m))
        out.push_back("the body's ground clearance must be in [0, its top)");
    if (!(low_band_top_m >= 0.0 && low_band_top_m <= 1.0))
        out.push_back("low_band_top_m must be in [0, 1]");
    return out;
}

ObstacleLayer::ObstacleLayer(const Costmap& geometry, const ObstacleLayerParams& params)
    : params_(params),
      grid_(geometry.origin_m, geometry.resolution_m, geometry.width, geometry.height) {
    if (params.threads > 1) threads_ = std::make_shared<Threads>(params.threads);
}

void ObstacleLayer::update_bounds(const Costmap&, const LayerInput& input, GridWindow& window) {
    if (!input.points_world) return;
    const Eigen::Vector2i s = grid_.cell_of(input.sensor_world_m.head<2>());
    // Unique endpoint cells: one ray per cell is enough to clear and mark (the cell's lowest
    // return, which clears the most). The per-cell scratch is kept between updates (zeroed cell by
    // cell at the end) instead of a grid-sized allocation per sweep, one struct per cell so that a
    // return costs one cache line.
    scratch_.resize(grid_.cost.size());
    top_.resize(grid_.cost.size(), 0.0f);
    grouped_.resize(grid_.cost.size(), 0);
    std::vector<int>& cells = cells_;
    cells.clear();
    const double mark2 = params_.mark_range_m * params_.mark_range_m;
    const double clear2 = params_.clear_range_m * params_.clear_range_m;
    const double low2 = params_.low_mark_range_m * params_.low_mark_range_m;
    // Each return's cell first, then the returns in order with the scratch of a return kAhead
    // further on prefetched: returns come in scan order and their cells lie across the grid, so
    // without it every new cell was a wait on memory.
    const std::vector<Eigen::Vector3f>& xyz = input.points_world->xyz;
    returns_.clear();
    for (std::size_t i = 0; i < xyz.size(); ++i) {
        const Eigen::Vector3f& p = xyz[i];
        if (!p.allFinite() || p.z() > params_.body.top_m) continue;
        const double d2 =
            (p.head<2>().cast<double>() - input.sensor_world_m.head<2>()).squaredNorm();
        if (d2 > clear2) continue;
        // grid_.cell_of's cell without its libm floor per return.
        const std::int64_t cx = floor_index(p.x() - grid_.origin_m.x(), grid_.resolution_m),
                           cy = floor_index(p.y() - grid_.origin_m.y(), grid_.resolution_m);
        if (cx < 0 || cy < 0 || cx >= grid_.width || cy >= grid_.height) continue;
        returns_.push_back({static_cast<int>(cy) * grid_.width + static_cast<int>(cx),
                            static_cast<std::uint32_t>(i), d2});
    }
    constexpr std::size_t kAhead = 16;
    for (std::size_t k = 0; k < returns_.size(); ++k) {
        if (k + kAhead < returns_.size()) {
            __builtin_prefetch(&scratch_[static_cast<std::size_t>(returns_[k + kAhead].cell)], 1);
            __builtin_prefetch(&top_[static_cast<std::size_t>(returns_[k + kAhead].cell)], 1);
        }
        const Eigen::Vector3f& p = xyz[returns_[k].point];
        const double d2 = returns_[k].d2;
        const int idx = returns_[k].cell;
        Scratch& e = scratch_[idx];
        if (e.endpoint == 0) {
            cells.push_back(idx);
            e.end_z = p.z();
            e.endpoint = 1;
        }
        e.end_z = std::min(e.end_z, p.z());
        if (!params_.body.can_hit(p.z()) || d2 > mark2) {
            if (p.z() < params_.low_band_top_m && e.floor < 65535) ++e.floor;
            if (p.z() < params_.body.ground_clearance_m && d2 <= low2 && e.bare < 65535) ++e.bare;
            continue;
        }
        if (p.z() >= params_.low_band_top_m) {
            top_[idx] = e.endpoint == 2 ? std::max(top_[idx], p.z()) : p.z();
            e.endpoint = 2;
        } else if (d2 <= low2 && e.low < 65535) {
            ++e.low;
            e.low_top = e.low == 1 ? p.z() : std::max(e.low_top, p.z());
        }
    }
    // Low returns mark a cell when enough of them, and a large enough share of the cell's returns
    // below the low band's top, stand above the clearance (floor noise lifts a few, not a share).
    for (int idx : cells) {
        Scratch& e = scratch_[idx];
        if (e.endpoint != 2 && e.low >= params_.low_min_returns &&
            e.low >= params_.low_min_share * (e.low + e.floor)) {
            e.endpoint = 2;
            top_[idx] = e.low_top;
        }
    }
    // The window is where a cell's cost changed, not everywhere a ray went: on a standing robot, or
    // along walls seen sweep after sweep, most rays change nothing, and the layers below (inflation
    // above all) then work on a few cells instead of the sensor's whole range.
    GridWindow changed;
    const double sensor_z = input.sensor_world_m.z();
    const int bw = (grid_.width + kBlock - 1) / kBlock, bh = (grid_.height + kBlock - 1) / kBlock;
    block_marks_.resize(static_cast<std::size_t>(bw) * bh, 0);
    auto block_of = [&](int x, int y) -> std::uint16_t& {
        return block_marks_[(y / kBlock) * bw + x / kBlock];
    };
    auto empty_block = [&](int bx, int by) {
        return bx < 0 || by < 0 || bx >= bw || by >= bh || block_marks_[by * bw + bx] == 0;
    };
    // Clear along each ray (ray_walk.hpp: Bresenham, stopping before the endpoint cell, crossing
    // blocks without marks in one step); a low mark only where the ray passes no higher than its
    // top (plus a noise margin). Whether a ray clears a cell depends on that cell's mark and the
    // ray alone, never on other rays: on several threads, each ray lists the cells it clears
    // against the grid as it was (its blocks' counts too, so it may walk cells another ray has
    // already freed), and the lists are applied afterwards; the same cells end up free.
    auto clears_cell = [&](int idx, double length, int x, int y) {
        const int i = y * grid_.width + x;
        if (grid_.cost[i] == cost::kFree || scratch_[i].endpoint == 2) return false;
        if (top_[i] >= params_.low_band_top_m)
            return true;  // tall marks: any ray (sparse rings rarely see their top)
        const double f = length > 0.0 ? std::sqrt(static_cast<double>((x - s.x()) * (x - s.x()) +
                                                                      (y - s.y()) * (y - s.y()))) /
                                            length
                                      : 0.0;
        return sensor_z + f * (scratch_[idx].end_z - sensor_z) <=
               top_[i] +
                   (grouped_[i] ? params_.low_clear_margin_m : params_.low_single_clear_margin_m);
    };
    auto free_cell = [&](int x, int y) {
        const int i = y * grid_.width + x;
        if (grid_.cost[i] == cost::kFree) return;
        grid_.cost[i] = cost::kFree;
        --block_of(x, y);
        changed.expand({x, y, x + 1, y + 1});
    };
    auto ray_length = [&](int idx) {
        const int ex = idx % grid_.width, ey = idx / grid_.width;
        return std::sqrt(
            static_cast<double>((ex - s.x()) * (ex - s.x()) + (ey - s.y()) * (ey - s.y())));
    };
    if (!threads_ || cells.size() < kParallelRays) {
        for (int idx : cells) {
            const double length = ray_length(idx);
            walk_ray(s.x(), s.y(), idx % grid_.width, idx / grid_.width, kBlock, empty_block,
                     [&](int x, int y) {
                         if (grid_.inside(x, y) && clears_cell(idx, length, x, y)) free_cell(x, y);
                     });
        }
    } else {
        tbb::enumerable_thread_specific<std::vector<int>> cleared;  // per thread: cells rays clear
        visible_parallel_for(
            threads_->arena, tbb::blocked_range<std::size_t>(0, cells.size(), 256),
            [&](const tbb::blocked_range<std::size_t>& part) {
                std::vector<int>& out = cleared.local();
                for (std::size_t k = part.begin(); k != part.end(); ++k) {
                    const int idx = cells[k];
                    const double length = ray_length(idx);
                    walk_ray(s.x(), s.y(), idx % grid_.width, idx / grid_.width, kBlock,
                             empty_block, [&](int x, int y) {
                                 if (grid_.inside(x, y) && clears_cell(idx, length, x, y))
                                     out.push_back(y * grid_.width + x);
                             });
                }
            });
        for (const std::vector<int>& list : cleared)
            for (int i : list) free_cell(i % grid_.width, i / grid_.width);
    }
    // A cell marked by returns below low_band_top_m (neighbours of a sweep's cells: in the grid).
    auto low_mark = [&](int x, int y) {
        const int i = y * grid_.width + x;
        return grid_.inside(x, y) && grid_.cost[i] != cost::kFree &&
               top_[i] < params_.low_band_top_m;
    };
    // This sweep's marks. And a low mark whose cell this sweep shows bare (low_min_returns floor
    // returns within low_mark_range_m, none on it) is cleared: the floor was seen there with
    // nothing standing on it. Rays passing over a low mark cannot clear it (above), so a mark that
    // floor noise or a pose error raised would otherwise stay until a ray came in below its top.
    for (int idx : cells) {
        const Scratch& e = scratch_[idx];
        const int x = idx % grid_.width, y = idx / grid_.width;
        if (e.endpoint == 2 && grid_.cost[idx] != cost::kLethal) {
            if (grid_.cost[idx] == cost::kFree) ++block_of(x, y);
            grid_.cost[idx] = cost::kLethal;
            changed.expand({x, y, x + 1, y + 1});
        } else if (e.endpoint != 2 && e.low == 0 && e.bare >= params_.low_min_returns &&
                   low_mark(x, y)) {
            free_cell(x, y);
        }
    }
    // Low marks with a low mark beside them are a part (a plate's edge, a runner), cleared only
    // from below their top; a low mark alone is cleared like noise (low_single_clear_margin_m).
    // Neighbours are read from the grid, so each cell's scratch is cleared as it is done.
    for (int idx : cells) {
        const int x = idx % grid_.width, y = idx / grid_.width;
        if (scratch_[idx].endpoint == 2 && top_[idx] < params_.low_band_top_m) {
            grouped_[idx] = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if ((dx != 0 || dy != 0) && low_mark(x + dx, y + dy))
                        grouped_[idx] = grouped_[(y + dy) * grid_.width + x + dx] = 1;
        }
        scratch_[idx] = Scratch{};
    }
    window.expand(changed.clipped(grid_.width, grid_.height));
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
