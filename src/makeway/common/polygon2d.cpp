#include "makeway/common/polygon2d.hpp"

#include <algorithm>
#include <limits>

namespace makeway {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

double signed_area(const Polygon2& polygon) {
    double twice = 0.0;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        const auto& p = polygon[i];
        const auto& q = polygon[(i + 1) % n];
        twice += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * twice;
}

Polygon2 clip_convex(const Polygon2& subject, const Polygon2& clip) {
    Polygon2 output = subject;
    const std::size_t m = clip.size();
    for (std::size_t e = 0; e < m && !output.empty(); ++e) {
        const Eigen::Vector2d& a = clip[e];
        const Eigen::Vector2d& b = clip[(e + 1) % m];
        const Polygon2 input = std::move(output);
        output.clear();
        const std::size_t n = input.size();
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d& p = input[i];
            const Eigen::Vector2d& q = input[(i + 1) % n];
            const double dp = cross(a, b, p);  // >= 0: p is inside (left of a->b)
            const double dq = cross(a, b, q);
            if (dp >= 0.0) output.push_back(p);
            if ((dp >= 0.0) != (dq >= 0.0)) {
                const double t = dp / (dp - dq);
                output.push_back(p + t * (q - p));
            }
        }
    }
    return output;
}

Polygon2 convex_hull(Polygon2 points) {
    if (points.size() < 3) return points;
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    Polygon2 hull(2 * points.size());
    std::size_t k = 0;
    for (const auto& p : points) {  // lower hull
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
        hull[k++] = p;
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);  // the last point repeats the first
    return hull;
}

double convex_distance(const Polygon2& polygon, const Eigen::Vector2d& p) {
    if (polygon.empty()) return std::numeric_limits<double>::infinity();
    bool left = true, right = true;  // p on one side of every edge: inside
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector2d& a = polygon[i];
        const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
        const Eigen::Vector2d ab = b - a, ap = p - a;
        const double cross = ab.x() * ap.y() - ab.y() * ap.x();
        left = left && cross >= 0.0;
        right = right && cross <= 0.0;
        const double len2 = ab.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp(ab.dot(ap) / len2, 0.0, 1.0) : 0.0;
        nearest = std::min(nearest, (ap - t * ab).norm());
    }
    return left || right ? 0.0 : nearest;
}

}  // namespace makeway
