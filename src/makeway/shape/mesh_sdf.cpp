#include "makeway/shape/mesh_sdf.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "makeway/common/random.hpp"

namespace makeway::shape {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Ericson, Real-Time Collision Detection 5.1.5: which Voronoi region of the triangle holds p.
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = va + vb + vc;
    if (!(std::abs(denom) > 0.0)) return a;  // degenerate triangle
    return a + ab * (vb / denom) + ac * (vc / denom);
}

MeshSdf::MeshSdf(const TriangleMesh& mesh, const Eigen::Vector3d& offset, double scale) {
    if (mesh.triangles.empty()) throw std::invalid_argument("mesh has no triangles");
    if (const std::string e = mesh.validity_error(); !e.empty()) throw std::invalid_argument(e);
    vertices_.reserve(mesh.vertices_m.size());
    for (const auto& v : mesh.vertices_m) vertices_.push_back((v.cast<double>() - offset) * scale);
    triangles_ = mesh.triangles;
    order_.resize(triangles_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
    nodes_.reserve(2 * triangles_.size());
    build(0, static_cast<int>(triangles_.size()));
    double area = 0.0;
    for (const auto& t : triangles_) {
        area += 0.5 *
                (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]).norm();
        cumulative_area_.push_back(area);
    }
}

int MeshSdf::build(int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Eigen::AlignedBox3d box;
    for (int k = first; k < first + count; ++k) {
        for (int j = 0; j < 3; ++j) box.extend(vertices_[triangles_[order_[k]][j]]);
    }
    nodes_[index].box = box;
    if (count <= 4) {
        nodes_[index].first = first;
        nodes_[index].count = count;
        return index;
    }
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    auto centroid = [&](int t) {
        return vertices_[triangles_[t][0]][axis] + vertices_[triangles_[t][1]][axis] +
               vertices_[triangles_[t][2]][axis];
    };
    const int half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half,
                     order_.begin() + first + count,
                     [&](int a, int b) { return centroid(a) < centroid(b); });
    const int left = build(first, half);
    const int right = build(first + half, count - half);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

double MeshSdf::box_distance2(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& q) const {
    const Eigen::Vector3d d = (box.min() - q).cwiseMax(q - box.max()).cwiseMax(0.0);
    return d.squaredNorm();
}

double MeshSdf::unsigned_distance(const Eigen::Vector3d& q) const {
    double best = std::numeric_limits<double>::infinity();
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
        if (box_distance2(n.box, q) >= best) continue;
        if (n.left < 0) {
            for (int k = n.first; k < n.first + n.count; ++k) {
                const Eigen::Vector3i& t =
                    triangles_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
                const double d2 = (closest_point_on_triangle(q, vertices_[t[0]], vertices_[t[1]],
                                                             vertices_[t[2]]) -
                                   q)
                                      .squaredNorm();
                best = std::min(best, d2);
            }
            continue;
        }
        const double dl = box_distance2(nodes_[static_cast<std::size_t>(n.left)].box, q);
        const double dr = box_distance2(nodes_[static_cast<std::size_t>(n.right)].box, q);
        // Nearest child last on the stack, so it is searched first.
        if (dl < dr) {
            stack[top++] = n.right;
            stack[top++] = n.left;
        } else {
            stack[top++] = n.left;
            stack[top++] = n.right;
        }
    }
    return std::sqrt(best);
}

double MeshSdf::winding_number(const Eigen::Vector3d& q) const {
    double total = 0.0;
    for (const auto& t : triangles_) {
        const Eigen::Vector3d a = vertices_[t[0]] - q, b = vertices_[t[1]] - q,
                              c = vertices_[t[2]] - q;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double det = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * std::atan2(det, den);
    }
    return total / (4.0 * M_PI);
}

std::vector<Eigen::Vector3d> MeshSdf::sample_surface(std::size_t count, std::uint64_t seed) const {
    std::vector<Eigen::Vector3d> out;
    out.reserve(count);
    Rng rng = make_rng(seed, 23);
    const double total = cumulative_area_.back();
    for (std::size_t i = 0; i < count; ++i) {
        const double u = uniform(rng, 0.0, total);
        const auto it = std::upper_bound(cumulative_area_.begin(), cumulative_area_.end(), u);
        const auto& t = triangles_[static_cast<std::size_t>(std::min<std::ptrdiff_t>(
            it - cumulative_area_.begin(), static_cast<std::ptrdiff_t>(triangles_.size()) - 1))];
        double r1 = uniform(rng, 0.0, 1.0), r2 = uniform(rng, 0.0, 1.0);
        if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
        out.push_back(vertices_[t[0]] + r1 * (vertices_[t[1]] - vertices_[t[0]]) +
                      r2 * (vertices_[t[2]] - vertices_[t[0]]));
    }
    return out;
}

}  // namespace makeway::shape
