#include "makeway/costmap/learned_zone.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "makeway/costmap/param_tables.hpp"

namespace makeway::costmap {
namespace {

// Phi(z), the standard normal CDF.
double normal_cdf(double z) { return 0.5 * std::erfc(-z * M_SQRT1_2); }

constexpr double kRasterCell_m = 0.02, kSizeStep_m = 0.005;

// One motion's smoothed footprint at q (object frame), c = cos(dyaw), sn = sin(dyaw): the term of
// c_learned without its weight; 0 beyond 4 kernels past the footprint's edges (the factor is below
// 3e-5 there).
double footprint_term(const ZoneMotion& m, double c, double sn, const Eigen::Vector2d& half,
                      double s, const Eigen::Vector2d& q) {
    const double dx = q.x() - m.dx_m, dy = q.y() - m.dy_m;
    const double x = std::abs(c * dx + sn * dy), y = std::abs(-sn * dx + c * dy);
    if (x > half.x() + 4.0 * s || y > half.y() + 4.0 * s) return 0.0;
    return normal_cdf((half.x() - x) / s) * normal_cdf((half.y() - y) / s);
}

}  // namespace

// c_learned on a square grid around the object centre, cell centres at origin + cell (i + 1/2).
// Outside the anonymous namespace: CoverageCache (declared in the header) holds it.
struct CoverageRaster {
    Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
    int n = 0;
    std::vector<float> c;

    double at(const Eigen::Vector2d& q) const {
        const Eigen::Vector2d g = (q - origin_m) / kRasterCell_m - Eigen::Vector2d(0.5, 0.5);
        const double fx = std::floor(g.x()), fy = std::floor(g.y());
        const int x = static_cast<int>(fx), y = static_cast<int>(fy);
        if (x < 0 || y < 0 || x + 1 >= n || y + 1 >= n) return 0.0;  // beyond the reach
        const double ax = g.x() - fx, ay = g.y() - fy;
        const auto v = [&](int i, int j) { return static_cast<double>(c[j * n + i]); };
        return (1 - ay) * ((1 - ax) * v(x, y) + ax * v(x + 1, y)) +
               ay * ((1 - ax) * v(x, y + 1) + ax * v(x + 1, y + 1));
    }
};

class CoverageCache {
  public:
    std::shared_ptr<const CoverageRaster> get(ObjectClass cls, const ClassZone& zone,
                                              double kernel_m, const Eigen::Vector2d& half_m) {
        const auto key =
            std::make_tuple(static_cast<int>(cls), std::lround(half_m.x() / kSizeStep_m),
                            std::lround(half_m.y() / kSizeStep_m));
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (const auto it = rasters_.find(key); it != rasters_.end()) return it->second;
        }
        const Eigen::Vector2d half(std::get<1>(key) * kSizeStep_m, std::get<2>(key) * kSizeStep_m);
        auto r = std::make_shared<CoverageRaster>();
        const double reach = learned_reach_m(zone, kernel_m, half) + kRasterCell_m;
        r->n = 2 * static_cast<int>(std::ceil(reach / kRasterCell_m)) + 2;
        r->origin_m = Eigen::Vector2d::Constant(-0.5 * r->n * kRasterCell_m);
        // Each motion splats its smoothed footprint onto the cells it can reach (4 kernels past
        // its edges), so the work is motions x footprint cells, not motions x raster cells.
        std::vector<double> sum(static_cast<std::size_t>(r->n) * r->n, 0.0);
        const double s = std::max(kernel_m, 1e-4);
        double total = 0.0;
        for (const ZoneMotion& m : zone.motions) {
            total += m.weight;
            const double c = std::cos(m.dyaw_rad), sn = std::sin(m.dyaw_rad);
            const Eigen::Vector2d grown = half + Eigen::Vector2d::Constant(4.0 * s);
            const double ex = std::abs(c) * grown.x() + std::abs(sn) * grown.y(),
                         ey = std::abs(sn) * grown.x() + std::abs(c) * grown.y();
            const auto cell_of = [&](double v, int axis) {
                return static_cast<int>(std::floor((v - r->origin_m[axis]) / kRasterCell_m));
            };
            const int x0 = std::max(0, cell_of(m.dx_m - ex, 0)),
                      x1 = std::min(r->n - 1, cell_of(m.dx_m + ex, 0)),
                      y0 = std::max(0, cell_of(m.dy_m - ey, 1)),
                      y1 = std::min(r->n - 1, cell_of(m.dy_m + ey, 1));
            for (int j = y0; j <= y1; ++j) {
                for (int i = x0; i <= x1; ++i) {
                    const Eigen::Vector2d q =
                        r->origin_m + kRasterCell_m * Eigen::Vector2d(i + 0.5, j + 0.5);
                    sum[j * r->n + i] += m.weight * footprint_term(m, c, sn, half, s, q);
                }
            }
        }
        r->c.resize(sum.size());
        for (std::size_t k = 0; k < sum.size(); ++k)
            r->c[k] = total > 0.0 ? static_cast<float>(sum[k] / total) : 0.0f;
        std::lock_guard<std::mutex> lock(mutex_);
        if (rasters_.size() >= 64) rasters_.clear();  // footprints seen lately are few
        return rasters_.emplace(key, std::move(r)).first->second;
    }

  private:
    std::mutex mutex_;
    std::map<std::tuple<int, long, long>, std::shared_ptr<const CoverageRaster>> rasters_;
};

LearnedZones::FreshCache::FreshCache() : cache(std::make_shared<CoverageCache>()) {}

double LearnedZones::coverage(ObjectClass cls, const Eigen::Vector2d& half_m,
                              const Eigen::Vector2d& q_object_m) const {
    const ClassZone* zone = of(cls);
    if (zone == nullptr) return 0.0;
    return cache_.cache->get(cls, *zone, kernel_m, half_m)->at(q_object_m);
}

std::vector<std::string> LearnedZones::validate() const {
    std::vector<std::string> out = learned_zones_table().problems(*this);
    const auto check = [&](const char* name, const std::optional<ClassZone>& z) {
        if (!z) return;
        if (!std::isfinite(z->observations) || z->observations < 0.0)
            out.push_back(std::string(name) + ".observations must be a number >= 0");
        if (z->observations > 0.0 && z->motions.empty())
            out.push_back(std::string(name) + " has observations but no motions");
        if (z->motions.size() > 20000)  // binned motions of one class: hundreds
            out.push_back(std::string(name) + ".motions: at most 20000 (bin them coarser)");
        double total = 0.0;
        for (const ZoneMotion& m : z->motions) {
            const bool finite = std::isfinite(m.dx_m) && std::isfinite(m.dy_m) &&
                                std::isfinite(m.dyaw_rad) && std::isfinite(m.weight);
            if (!finite || m.weight < 0.0 || std::hypot(m.dx_m, m.dy_m) > kMaxZoneMotion_m) {
                out.push_back(std::string(name) +
                              ".motions: each needs |(dx, dy)| <= 5 m and a weight >= 0, all "
                              "finite");
                return;
            }
            total += m.weight;
        }
        if (!z->motions.empty() && total <= 0.0)
            out.push_back(std::string(name) + ".motions: the weights sum to 0");
    };
    check("chair", chair);
    check("table", table);
    return out;
}

double learned_coverage(const ClassZone& zone, double kernel_m, const Eigen::Vector2d& half_m,
                        const Eigen::Vector2d& q) {
    double sum = 0.0, total = 0.0;
    const double s = std::max(kernel_m, 1e-4);
    for (const ZoneMotion& m : zone.motions) {
        total += m.weight;
        sum +=
            m.weight * footprint_term(m, std::cos(m.dyaw_rad), std::sin(m.dyaw_rad), half_m, s, q);
    }
    return total > 0.0 ? sum / total : 0.0;
}

double learned_reach_m(const ClassZone& zone, double kernel_m, const Eigen::Vector2d& half_m) {
    double far = 0.0;
    for (const ZoneMotion& m : zone.motions) far = std::max(far, std::hypot(m.dx_m, m.dy_m));
    return far + half_m.norm() + 4.0 * kernel_m;
}

}  // namespace makeway::costmap
