#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/triangle_mesh.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::sim::testing_util {

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
inline double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                      const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return (p - a).norm();
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return (p - b).norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return (p - c).norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    }
    const double denom = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

inline double mesh_distance(const TriangleMesh& m, const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : m.triangles) {
        best = std::min(best, point_triangle_distance(p, m.vertices_m[t[0]].cast<double>(),
                                                      m.vertices_m[t[1]].cast<double>(),
                                                      m.vertices_m[t[2]].cast<double>()));
    }
    return best;
}

/// A closed square room of inner half-size `half_m` (walls 0.2 m thick), ceiling at 3 m.
inline Scene box_room(double half_m) {
    Scene s;
    s.floor_min_m = Eigen::Vector2d(-half_m - 1, -half_m - 1);
    s.floor_max_m = Eigen::Vector2d(half_m + 1, half_m + 1);
    s.ceiling_height_m = 3.0;
    const double c = half_m + 0.1;
    s.walls = {{{-c, -c}, {c, -c}, 0.2, 3.0},
               {{c, -c}, {c, c}, 0.2, 3.0},
               {{c, c}, {-c, c}, 0.2, 3.0},
               {{-c, c}, {-c, -c}, 0.2, 3.0}};
    return s;
}

}  // namespace makeway::sim::testing_util
