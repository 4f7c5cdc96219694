#include "makeway/costmap/learned_zone.hpp"

#include <algorithm>
#include <cmath>

#include "makeway/costmap/param_tables.hpp"

namespace makeway::costmap {
namespace {

// Phi(z), the standard normal CDF.
double normal_cdf(double z) { return 0.5 * std::erfc(-z * M_SQRT1_2); }

}  // namespace

std::vector<std::string> LearnedZones::validate() const {
    std::vector<std::string> out = learned_zones_table().problems(*this);
    const auto check = [&](const char* name, const std::optional<ClassZone>& z) {
        if (!z) return;
        if (!std::isfinite(z->observations) || z->observations < 0.0)
            out.push_back(std::string(name) + ".observations must be a number >= 0");
        if (z->observations > 0.0 && z->motions.empty())
            out.push_back(std::string(name) + " has observations but no motions");
        double total = 0.0;
        for (const ZoneMotion& m : z->motions) {
            const bool finite = std::isfinite(m.dx_m) && std::isfinite(m.dy_m) &&
                                std::isfinite(m.dyaw_rad) && std::isfinite(m.weight);
            if (!finite || m.weight < 0.0 || std::hypot(m.dx_m, m.dy_m) > 20.0) {
                out.push_back(std::string(name) +
                              ".motions: each needs |(dx, dy)| <= 20 m and a weight >= 0, all "
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
        const double dx = q.x() - m.dx_m, dy = q.y() - m.dy_m;
        const double c = std::cos(m.dyaw_rad), sn = std::sin(m.dyaw_rad);
        const double x = std::abs(c * dx + sn * dy), y = std::abs(-sn * dx + c * dy);
        // Beyond 4 kernels outside the footprint the factor is below 3e-5: skip the erfc.
        if (x > half_m.x() + 4.0 * s || y > half_m.y() + 4.0 * s) continue;
        sum += m.weight * normal_cdf((half_m.x() - x) / s) * normal_cdf((half_m.y() - y) / s);
    }
    return total > 0.0 ? sum / total : 0.0;
}

double learned_reach_m(const ClassZone& zone, double kernel_m, const Eigen::Vector2d& half_m) {
    double far = 0.0;
    for (const ZoneMotion& m : zone.motions) far = std::max(far, std::hypot(m.dx_m, m.dy_m));
    return far + half_m.norm() + 4.0 * kernel_m;
}

}  // namespace makeway::costmap
