#include "makeway/shape/volume.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <unordered_map>

namespace makeway::shape {

std::vector<Eigen::Vector3d> CubeGrid::centres() const {
    std::vector<Eigen::Vector3d> out;
    out.reserve(size());
    for (int z = 0; z < resolution; ++z)
        for (int y = 0; y < resolution; ++y)
            for (int x = 0; x < resolution; ++x) out.push_back(centre(x, y, z));
    return out;
}

TsdfVolume::TsdfVolume(const CubeGrid& grid, double truncation_cells)
    : grid_(grid),
      truncation_(truncation_cells * grid.cell()),
      tsdf_(grid.size(), 1.0f),
      weight_(grid.size(), 0.0f) {}

std::size_t TsdfVolume::observed_cells() const {
    return static_cast<std::size_t>(
        std::count_if(weight_.begin(), weight_.end(), [](float w) { return w > 0.0f; }));
}

void TsdfVolume::integrate(const std::vector<Eigen::Vector3d>& points,
                           const Eigen::Vector3d& origin) {
    if (!origin.allFinite()) return;
    const double h = grid_.half_extent, step = 0.5 * grid_.cell();
    const int n = grid_.resolution;
    std::vector<std::size_t> touched;
    for (const Eigen::Vector3d& p : points) {
        if (!p.allFinite()) continue;
        const Eigen::Vector3d d = p - origin;
        const double range = d.norm();
        if (!(range > 1e-9)) continue;
        const Eigen::Vector3d u = d / range;
        // Slab test: where the ray is inside the cube.
        double t0 = 0.0, t1 = range + truncation_;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(u[a]) < 1e-12) {
                if (origin[a] < -h || origin[a] > h) t1 = -1.0;
                continue;
            }
            double ta = (-h - origin[a]) / u[a], tb = (h - origin[a]) / u[a];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        if (t0 > t1) continue;
        touched.clear();
        for (double t = t0; t <= t1; t += step) {
            const Eigen::Vector3d q = origin + t * u;
            const Eigen::Array3i c = ((q.array() + h) / grid_.cell()).floor().cast<int>();
            if ((c < 0).any() || (c >= n).any()) continue;
            const std::size_t i = grid_.index(c.x(), c.y(), c.z());
            if (std::find(touched.begin(), touched.end(), i) != touched.end())
                continue;  // once per ray
            touched.push_back(i);
            // The signed distance along the ray from the cell's centre to the return.
            const double along = (grid_.centre(c.x(), c.y(), c.z()) - origin).dot(u);
            const double sdf = range - along;
            if (sdf < -truncation_) continue;
            const float value = static_cast<float>(std::clamp(sdf / truncation_, -1.0, 1.0));
            float& w = weight_[i];
            tsdf_[i] = (tsdf_[i] * w + value) / (w + 1.0f);
            w += 1.0f;
        }
    }
}

namespace {

// Cube corners (x, y, z offsets) and the six tetrahedra around the 0-6 diagonal.
constexpr std::array<std::array<int, 3>, 8> kCorner{
    {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
constexpr std::array<std::array<int, 4>, 6> kTet{
    {{0, 5, 1, 6}, {0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}}};

}  // namespace

TriangleMesh extract_isosurface(const std::vector<float>& values, const Eigen::Vector3i& dims,
                                const Eigen::Vector3d& origin, double spacing, double level,
                                bool inside_below) {
    TriangleMesh mesh;
    if ((dims.array() < 2).any() || values.size() != static_cast<std::size_t>(dims.prod()))
        return mesh;
    auto node = [&](int x, int y, int z) {
        return (static_cast<std::size_t>(z) * static_cast<std::size_t>(dims.y()) +
                static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(dims.x()) +
               static_cast<std::size_t>(x);
    };
    auto is_inside = [&](std::size_t i) {
        const float v = values[i];
        if (!std::isfinite(v)) return false;
        return inside_below ? v < level : v > level;
    };
    auto position = [&](std::size_t i) {
        const auto x = static_cast<double>(i % static_cast<std::size_t>(dims.x()));
        const auto y = static_cast<double>((i / static_cast<std::size_t>(dims.x())) %
                                           static_cast<std::size_t>(dims.y()));
        const auto z = static_cast<double>(
            i / (static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y())));
        return Eigen::Vector3d(origin + spacing * Eigen::Vector3d(x, y, z));
    };
    std::unordered_map<std::uint64_t, int> edge_vertex;
    auto vertex_on = [&](std::size_t a, std::size_t b) {  // a inside, b outside
        // Interpolate in a canonical order so both cells sharing the edge get the same point. The
        // topology comes from the signs alone (always closed and manifold); a crossing exactly at
        // a node is kept a thousandth of the edge off it, so vertices of different edges never
        // coincide and no triangle degenerates.
        const std::size_t lo = std::min(a, b), hi = std::max(a, b);
        const double vl = values[lo], vh = values[hi];
        double t = 0.5;
        if (std::isfinite(vl) && std::isfinite(vh) && std::abs(vh - vl) > 1e-12)
            t = std::clamp((level - vl) / (vh - vl), 1e-3, 1.0 - 1e-3);
        const std::uint64_t key = lo * static_cast<std::uint64_t>(values.size()) + hi;
        if (const auto it = edge_vertex.find(key); it != edge_vertex.end()) return it->second;
        const Eigen::Vector3d p = position(lo) + t * (position(hi) - position(lo));
        const int index = static_cast<int>(mesh.vertices_m.size());
        mesh.vertices_m.push_back(p.cast<float>());
        edge_vertex.emplace(key, index);
        return index;
    };
    auto add = [&](int a, int b, int c, const Eigen::Vector3d& towards_outside) {
        const Eigen::Vector3d pa = mesh.vertices_m[static_cast<std::size_t>(a)].cast<double>();
        const Eigen::Vector3d n =
            (mesh.vertices_m[static_cast<std::size_t>(b)].cast<double>() - pa)
                .cross(mesh.vertices_m[static_cast<std::size_t>(c)].cast<double>() - pa);
        if (a == b || b == c || a == c) return;
        if (n.dot(towards_outside) < 0.0) std::swap(b, c);
        mesh.triangles.emplace_back(a, b, c);
    };
    for (int z = 0; z + 1 < dims.z(); ++z) {
        for (int y = 0; y + 1 < dims.y(); ++y) {
            for (int x = 0; x + 1 < dims.x(); ++x) {
                std::array<std::size_t, 8> c{};
                for (int k = 0; k < 8; ++k)
                    c[static_cast<std::size_t>(k)] =
                        node(x + kCorner[static_cast<std::size_t>(k)][0],
                             y + kCorner[static_cast<std::size_t>(k)][1],
                             z + kCorner[static_cast<std::size_t>(k)][2]);
                for (const auto& tet : kTet) {
                    std::array<std::size_t, 4> in{}, out{};
                    int ni = 0, no = 0;
                    for (const int k : tet) {
                        const std::size_t i = c[static_cast<std::size_t>(k)];
                        if (is_inside(i))
                            in[static_cast<std::size_t>(ni++)] = i;
                        else
                            out[static_cast<std::size_t>(no++)] = i;
                    }
                    if (ni == 0 || no == 0) continue;
                    Eigen::Vector3d ci = Eigen::Vector3d::Zero(), co = Eigen::Vector3d::Zero();
                    for (int k = 0; k < ni; ++k)
                        ci += position(in[static_cast<std::size_t>(k)]) / ni;
                    for (int k = 0; k < no; ++k)
                        co += position(out[static_cast<std::size_t>(k)]) / no;
                    const Eigen::Vector3d dir = co - ci;
                    if (ni == 1) {
                        add(vertex_on(in[0], out[0]), vertex_on(in[0], out[1]),
                            vertex_on(in[0], out[2]), dir);
                    } else if (ni == 3) {
                        add(vertex_on(in[0], out[0]), vertex_on(in[1], out[0]),
                            vertex_on(in[2], out[0]), dir);
                    } else {  // two and two: a quad, split along one diagonal
                        const int a = vertex_on(in[0], out[0]), b = vertex_on(in[0], out[1]);
                        const int cc = vertex_on(in[1], out[1]), d = vertex_on(in[1], out[0]);
                        add(a, b, cc, dir);
                        add(a, cc, d, dir);
                    }
                }
            }
        }
    }
    return mesh;
}

namespace {
struct CloudAdaptor {
    const std::vector<Eigen::Vector3d>* pts;
    std::size_t kdtree_get_point_count() const { return pts->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const {
        return (*pts)[i][static_cast<Eigen::Index>(d)];
    }
    template <class B>
    bool kdtree_get_bbox(B&) const {
        return false;
    }
};
using CloudTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
                                        CloudAdaptor, 3, std::size_t>;

double mean_nearest(const std::vector<Eigen::Vector3d>& from,
                    const std::vector<Eigen::Vector3d>& to) {
    const CloudAdaptor adaptor{&to};
    CloudTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    double sum = 0.0;
    for (const auto& q : from) {
        std::size_t index = 0;
        double d2 = 0.0;
        nanoflann::KNNResultSet<double, std::size_t> found(1);
        found.init(&index, &d2);
        tree.findNeighbors(found, q.data(), nanoflann::SearchParams());
        sum += std::sqrt(d2);
    }
    return sum / static_cast<double>(from.size());
}
}  // namespace

double chamfer_l1(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    return 0.5 * (mean_nearest(a, b) + mean_nearest(b, a));
}

double volumetric_iou(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    std::size_t both = 0, either = 0;
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
        both += (a[i] && b[i]);
        either += (a[i] || b[i]);
    }
    return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

}  // namespace makeway::shape
