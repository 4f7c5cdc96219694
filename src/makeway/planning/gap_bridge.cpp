#include "makeway/planning/gap_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>
#include <utility>

#include "makeway/common/floor_index.hpp"

namespace makeway::planning {
namespace {

// A set of grid cells: a bitmap over a box (the caller's returns near the robot span a few
// thousand cells), and a hash set for any cell outside it. The monitor calls bridge_gaps every
// cycle, and hashing the 9 cells around every pair's middle was most of its time.
class CellSet {
  public:
    CellSet(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
        constexpr std::int64_t kMaxCells = std::int64_t{1} << 22;  // 4 MB
        const std::int64_t w = x1 - x0 + 1, h = y1 - y0 + 1;
        if (w <= 0 || h <= 0 || w > kMaxCells || h > kMaxCells / w) return;  // all hashed
        x0_ = x0;
        y0_ = y0;
        w_ = w;
        h_ = h;
        bits_.assign(static_cast<std::size_t>(w * h), 0);
    }
    bool contains(std::int64_t ix, std::int64_t iy) const {
        const std::int64_t i = index(ix, iy);
        return i >= 0 ? bits_[static_cast<std::size_t>(i)] != 0
                      : other_.count(cell_key(ix, iy)) != 0;
    }
    /// True when the cell was not in the set.
    bool insert(std::int64_t ix, std::int64_t iy) {
        const std::int64_t i = index(ix, iy);
        if (i < 0) return other_.insert(cell_key(ix, iy)).second;
        char& b = bits_[static_cast<std::size_t>(i)];
        const bool fresh = b == 0;
        b = 1;
        return fresh;
    }

  private:
    std::int64_t index(std::int64_t ix, std::int64_t iy) const {
        const std::int64_t x = ix - x0_, y = iy - y0_;
        return x >= 0 && y >= 0 && x < w_ && y < h_ ? y * w_ + x : -1;
    }
    std::int64_t x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
    std::vector<char> bits_;
    std::unordered_set<std::int64_t> other_;
};

}  // namespace

std::vector<Eigen::Vector2d> bridge_gaps(const std::vector<Eigen::Vector2d>& pts, double gap_m,
                                         double step_m) {
    std::vector<Eigen::Vector2d> out;
    if (!(gap_m > 2.0 * step_m) || !(step_m > 0.0) || pts.size() < 2) return out;
    // The returns' own cells (the gap test) and, in a second set, the points added too (no
    // duplicates); both over the returns' box grown by the cells around a middle.
    std::int64_t x0 = floor_index(pts[0].x(), step_m), x1 = x0;
    std::int64_t y0 = floor_index(pts[0].y(), step_m), y1 = y0;
    for (const Eigen::Vector2d& q : pts) {
        const std::int64_t ix = floor_index(q.x(), step_m), iy = floor_index(q.y(), step_m);
        x0 = std::min(x0, ix), x1 = std::max(x1, ix), y0 = std::min(y0, iy), y1 = std::max(y1, iy);
    }
    CellSet occupied(x0 - 2, y0 - 2, x1 + 2, y1 + 2);
    CellSet filled(x0 - 2, y0 - 2, x1 + 2, y1 + 2);
    for (const Eigen::Vector2d& q : pts) {
        const std::int64_t ix = floor_index(q.x(), step_m), iy = floor_index(q.y(), step_m);
        occupied.insert(ix, iy);
        filled.insert(ix, iy);
    }
    auto around_occupied = [&](const Eigen::Vector2d& q) {
        for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = -1; dy <= 1; ++dy) {
                const Eigen::Vector2d p = q + step_m * Eigen::Vector2d(dx, dy);
                if (occupied.contains(floor_index(p.x(), step_m), floor_index(p.y(), step_m)))
                    return true;
            }
        }
        return false;
    };
    // Pairs from neighbouring cells gap_m wide only (each return meets the few near it): the
    // returns sorted by that cell (in their order within one), each cell's run found by search.
    std::vector<std::pair<std::int64_t, std::int64_t>> bucket(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i)
        bucket[i] = {floor_index(pts[i].x(), gap_m), floor_index(pts[i].y(), gap_m)};
    std::vector<std::size_t> order(pts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return bucket[a] < bucket[b]; });
    const double min2 = 4.0 * step_m * step_m, max2 = gap_m * gap_m;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto [bx, by] = bucket[i];
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const std::pair<std::int64_t, std::int64_t> key(bx + dx, by + dy);
                auto it =
                    std::lower_bound(order.begin(), order.end(), key,
                                     [&](std::size_t a, const auto& k) { return bucket[a] < k; });
                for (; it != order.end() && bucket[*it] == key; ++it) {
                    const std::size_t j = *it;
                    if (j <= i) continue;  // each pair once
                    const Eigen::Vector2d d = pts[j] - pts[i];
                    const double n2 = d.squaredNorm();
                    if (n2 <= min2 || n2 > max2 || around_occupied(pts[i] + 0.5 * d)) continue;
                    const int n = static_cast<int>(std::ceil(std::sqrt(n2) / step_m));
                    for (int k = 1; k < n; ++k) {
                        const Eigen::Vector2d q = pts[i] + d * (static_cast<double>(k) / n);
                        if (filled.insert(floor_index(q.x(), step_m), floor_index(q.y(), step_m)))
                            out.push_back(q);
                    }
                }
            }
        }
    }
    return out;
}

}  // namespace makeway::planning
