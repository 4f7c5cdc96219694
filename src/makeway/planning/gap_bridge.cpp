#include "makeway/planning/gap_bridge.hpp"

#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace makeway::planning {

std::vector<Eigen::Vector2d> bridge_gaps(const std::vector<Eigen::Vector2d>& pts, double gap_m,
                                         double step_m) {
    std::vector<Eigen::Vector2d> out;
    if (!(gap_m > 2.0 * step_m) || !(step_m > 0.0) || pts.size() < 2) return out;
    auto cell = [step_m](const Eigen::Vector2d& q) {
        return cell_key(static_cast<std::int64_t>(std::floor(q.x() / step_m)),
                        static_cast<std::int64_t>(std::floor(q.y() / step_m)));
    };
    auto around = [&](const Eigen::Vector2d& q, const std::unordered_set<std::int64_t>& cells) {
        for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = -1; dy <= 1; ++dy) {
                if (cells.count(cell(q + step_m * Eigen::Vector2d(dx, dy)))) return true;
            }
        }
        return false;
    };
    std::unordered_set<std::int64_t> occupied;  // the returns' own cells: the gap test
    for (const Eigen::Vector2d& q : pts) occupied.insert(cell(q));
    std::unordered_set<std::int64_t> filled = occupied;  // and the points added: no duplicates
    // Pairs from neighbouring cells gap_m wide only (each return meets the few near it).
    auto bucket_of = [gap_m](const Eigen::Vector2d& q) {
        return std::pair<std::int64_t, std::int64_t>(
            static_cast<std::int64_t>(std::floor(q.x() / gap_m)),
            static_cast<std::int64_t>(std::floor(q.y() / gap_m)));
    };
    std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto [bx, by] = bucket_of(pts[i]);
        buckets[cell_key(bx, by)].push_back(i);
    }
    const double min2 = 4.0 * step_m * step_m, max2 = gap_m * gap_m;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto [bx, by] = bucket_of(pts[i]);
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const auto b = buckets.find(cell_key(bx + dx, by + dy));
                if (b == buckets.end()) continue;
                for (const std::size_t j : b->second) {
                    if (j <= i) continue;  // each pair once
                    const Eigen::Vector2d d = pts[j] - pts[i];
                    const double n2 = d.squaredNorm();
                    if (n2 <= min2 || n2 > max2 || around(pts[i] + 0.5 * d, occupied)) continue;
                    const int n = static_cast<int>(std::ceil(std::sqrt(n2) / step_m));
                    for (int k = 1; k < n; ++k) {
                        const Eigen::Vector2d q = pts[i] + d * (static_cast<double>(k) / n);
                        if (filled.insert(cell(q)).second) out.push_back(q);
                    }
                }
            }
        }
    }
    return out;
}

}  // namespace makeway::planning
