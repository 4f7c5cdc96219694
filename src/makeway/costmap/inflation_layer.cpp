#include "makeway/costmap/inflation_layer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/handover.hpp"
#include "makeway/costmap/param_tables.hpp"

namespace makeway::costmap {
namespace {

constexpr double kFar = 1e10;  // beyond any squared distance in cells, small enough to stay exact

// 1D squared distance transform of f (Felzenszwalb & Huttenlocher 2012, lower envelope of
// parabolas).
void dt1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
          std::vector<double>& z) {
    const int n = static_cast<int>(f.size());
    auto intersect = [&](int q, int p) {
        return ((f[q] + q * q) - (f[p] + p * p)) / (2.0 * q - 2.0 * p);
    };
    int k = 0;
    v[0] = 0;
    z[0] = -std::numeric_limits<double>::infinity();
    z[1] = std::numeric_limits<double>::infinity();
    for (int q = 1; q < n; ++q) {
        double s = intersect(q, v[k]);
        while (s <= z[k]) s = intersect(q, v[--k]);  // z[0] = -inf stops the loop
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        d[q] = (q - v[k]) * (q - v[k]) + f[v[k]];
    }
}

}  // namespace

struct InflationLayer::Threads {
    explicit Threads(int n) : arena(n) {}
    tbb::task_arena arena;
};

InflationLayer::InflationLayer(const InflationParams& params) : params_(params) {
    if (params.threads > 1) threads_ = std::make_shared<Threads>(params.threads);
}

std::vector<std::string> InflationParams::validate() const {
    std::vector<std::string> out = inflation_table().problems(*this);
    if (!(inscribed_radius_m > 0.0 && inscribed_radius_m < 5.0))
        out.push_back("inscribed_radius_m must be in (0, 5)");
    if (!(inflation_radius_m >= inscribed_radius_m && inflation_radius_m < 10.0)) {
        out.push_back("inflation_radius_m must be in [inscribed_radius_m, 10)");
    }
    return out;
}

std::uint8_t inflation_cost(double d, const InflationParams& p) {
    if (d <= 0.0) return cost::kLethal;
    if (d <= p.inscribed_radius_m) return cost::kInscribed;
    if (d > p.inflation_radius_m) return cost::kFree;
    return static_cast<std::uint8_t>(std::max(
        1.0, std::floor(cost::kMaxSoft * std::exp(-p.cost_scaling * (d - p.inscribed_radius_m)))));
}

namespace {

// The two passes: columns (two sweeps over the rows), then rows (dt1d, on the arena's threads when
// there is one: each line is transformed alone, with its own scratch, so the result does not
// depend on the threads).
std::vector<double> distance_transform(const Costmap& grid, const GridWindow& src,
                                       const GridWindow& win, tbb::task_arena* arena) {
    const int w = src.x1 - src.x0, h = src.y1 - src.y0;
    std::vector<double> g(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::uint8_t c = grid.at(src.x0 + x, src.y0 + y);
            g[static_cast<std::size_t>(y) * w + x] = (c == cost::kLethal) ? 0.0 : kFar;
        }
    }
    // Lines [l0, l1) of length n, element i of line l at g[l * line_step + i * step].
    auto pass = [&g](int l0, int l1, int n, std::size_t line_step, std::size_t step) {
        std::vector<double> f(n), d(n), z(n + 1);
        std::vector<int> v(n);
        for (int l = l0; l < l1; ++l) {
            double* line = g.data() + static_cast<std::size_t>(l) * line_step;
            for (int i = 0; i < n; ++i) f[i] = line[i * step];
            dt1d(f, d, v, z);
            for (int i = 0; i < n; ++i) line[i * step] = d[i];
        }
    };
    auto lines = [&](int count, int n, std::size_t line_step, std::size_t step) {
        if (!arena || count < 64) return pass(0, count, n, line_step, step);
        visible_parallel_for(*arena, tbb::blocked_range<int>(0, count, 32),
                             [&](const tbb::blocked_range<int>& part) {
                                 pass(part.begin(), part.end(), n, line_step, step);
                             });
    };
    // Columns: on a grid of 0 (lethal) and kFar the envelope is the squared distance to the
    // nearest lethal cell of the column (kFar where there is none), found row by row in two
    // sweeps, down and up, in memory order (what dt1d gives, to the bit: the same integers).
    std::vector<int> last(static_cast<std::size_t>(w));
    for (const int dir : {1, -1}) {
        std::fill(last.begin(), last.end(), -1);
        for (int y = dir > 0 ? 0 : h - 1; y >= 0 && y < h; y += dir) {
            double* row = g.data() + static_cast<std::size_t>(y) * w;
            for (int x = 0; x < w; ++x) {
                if (row[x] == 0.0) {
                    last[x] = y;
                } else if (last[x] >= 0) {
                    const double d = static_cast<double>(y - last[x]) * (y - last[x]);
                    row[x] = std::min(row[x], d);
                }
            }
        }
    }
    lines(h, w, static_cast<std::size_t>(w), 1);  // rows
    std::vector<double> out(static_cast<std::size_t>(win.x1 - win.x0) * (win.y1 - win.y0));
    for (int y = win.y0; y < win.y1; ++y) {
        for (int x = win.x0; x < win.x1; ++x) {
            out[static_cast<std::size_t>(y - win.y0) * (win.x1 - win.x0) + (x - win.x0)] =
                g[static_cast<std::size_t>(y - src.y0) * w + (x - src.x0)];
        }
    }
    return out;
}

}  // namespace

std::vector<double> squared_distance_to_lethal(const Costmap& grid, const GridWindow& source,
                                               const GridWindow& window) {
    return distance_transform(grid, source, window, nullptr);
}

void InflationLayer::update_bounds(const Costmap& master, const LayerInput&, GridWindow& window) {
    // A lethal cell that changed affects cells up to the inflation radius away.
    const int r = static_cast<int>(std::ceil(params_.inflation_radius_m / master.resolution_m));
    window = window.grown(r).clipped(master.width, master.height);
}

void InflationLayer::update_costs(Costmap& master, const GridWindow& window) {
    if (window.empty()) return;
    const int r = static_cast<int>(std::ceil(params_.inflation_radius_m / master.resolution_m));
    const GridWindow source = window.grown(r).clipped(master.width, master.height);
    const std::vector<double> d2 =
        distance_transform(master, source, window, threads_ ? &threads_->arena : nullptr);
    // Squared distances on the grid are whole numbers of cells^2: the cost of each one is tabled
    // once per resolution, out to the first beyond the inflation radius that is free (all farther
    // ones are: the distance only grows), so there is no sqrt and exp per cell.
    if (table_resolution_m_ != master.resolution_m) {
        table_resolution_m_ = master.resolution_m;
        const double reach2 = std::pow(params_.inflation_radius_m / master.resolution_m, 2);
        cost_of_d2_.clear();
        for (std::size_t k = 0;; ++k) {
            const std::uint8_t c =
                inflation_cost(std::sqrt(static_cast<double>(k)) * master.resolution_m, params_);
            if (c == cost::kFree && static_cast<double>(k) > reach2) break;
            cost_of_d2_.push_back(c);
        }
    }
    const double free_from = static_cast<double>(cost_of_d2_.size());
    const int ww = window.x1 - window.x0;
    for (int y = window.y0; y < window.y1; ++y) {
        for (int x = window.x0; x < window.x1; ++x) {
            const double k = d2[static_cast<std::size_t>(y - window.y0) * ww + (x - window.x0)];
            const std::uint8_t c =
                k < free_from ? cost_of_d2_[static_cast<std::size_t>(k)] : cost::kFree;
            std::uint8_t& m = master.at(x, y);
            if (c > m || (m == cost::kUnknown && c != cost::kFree)) m = c;
        }
    }
}

}  // namespace makeway::costmap
