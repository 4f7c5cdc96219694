#include "makeway/verification/closest_point_grid.hpp"

#include <cmath>
#include <limits>

namespace makeway::verification {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One line of the separable transform: d[q] = min_p (q - p)^2 + f[p], and the site carried by the
// minimising p. v, z are the envelope's parabola vertices and boundaries (scratch).
void transform_line(const double* f, const std::uint32_t* site, std::size_t n, double* d,
                    std::uint32_t* site_out, std::vector<int>& v, std::vector<double>& z) {
    v.resize(n);
    z.resize(n + 1);
    int k = -1;
    for (int q = 0; q < static_cast<int>(n); ++q) {
        if (f[q] == kInf) continue;
        double s = -kInf;
        while (k >= 0) {
            const int p = v[static_cast<std::size_t>(k)];
            s = ((f[q] + q * q) - (f[p] + p * p)) / (2.0 * (q - p));
            if (s > z[static_cast<std::size_t>(k)]) break;
            --k;
        }
        ++k;
        v[static_cast<std::size_t>(k)] = q;
        z[static_cast<std::size_t>(k)] = k == 0 ? -kInf : s;
        z[static_cast<std::size_t>(k) + 1] = kInf;
    }
    if (k < 0) {  // no site on this line
        for (std::size_t q = 0; q < n; ++q) d[q] = kInf, site_out[q] = ClosestPointGrid::kOutside;
        return;
    }
    int j = 0;
    for (int q = 0; q < static_cast<int>(n); ++q) {
        while (z[static_cast<std::size_t>(j) + 1] < q) ++j;
        const int p = v[static_cast<std::size_t>(j)];
        d[q] = (q - p) * (q - p) + f[p];
        site_out[q] = site[p];
    }
}

}  // namespace

ClosestPointGrid::ClosestPointGrid(const std::vector<Eigen::Vector3d>& points, double cell_m,
                                   double margin_m)
    : cell_m_(cell_m), inv_cell_m_(1.0 / cell_m) {
    if (points.empty() || !(cell_m > 0.0) || !(margin_m >= 0.0)) return;
    Eigen::Vector3d lo = points.front(), hi = points.front();
    for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    origin_m_ = lo - Eigen::Vector3d::Constant(margin_m);
    dims_ = ((hi - lo).array() / cell_m + 2.0 * margin_m / cell_m).ceil().cast<int>() + 1;
    const std::size_t nx = static_cast<std::size_t>(dims_.x()),
                      ny = static_cast<std::size_t>(dims_.y()),
                      nz = static_cast<std::size_t>(dims_.z());
    const std::size_t cells = nx * ny * nz;
    // Sites: each occupied cell keeps the point nearest its centre; squared distance 0 there.
    std::vector<double> dist(cells, kInf);
    nearest_.assign(cells, kOutside);
    std::vector<double> best(cells, kInf);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Eigen::Array3d f = (points[i] - origin_m_).array() / cell_m;
        const Eigen::Array3i c = f.cast<int>().min(dims_ - 1).max(0);
        const std::size_t idx =
            (static_cast<std::size_t>(c.z()) * ny + static_cast<std::size_t>(c.y())) * nx +
            static_cast<std::size_t>(c.x());
        const double off = (f - (c.cast<double>() + 0.5)).matrix().squaredNorm();
        if (off < best[idx])
            best[idx] = off, nearest_[idx] = static_cast<std::uint32_t>(i), dist[idx] = 0.0;
    }
    // Separable passes along x, y, z (squared distances in cell units between cell centres).
    const std::size_t longest = std::max({nx, ny, nz});
    std::vector<double> f(longest), d(longest);
    std::vector<std::uint32_t> s(longest), s_out(longest);
    std::vector<int> v;
    std::vector<double> z;
    const std::size_t stride[3] = {1, nx, nx * ny};
    const std::size_t len[3] = {nx, ny, nz};
    for (int axis = 0; axis < 3; ++axis) {
        const std::size_t n = len[axis], step = stride[axis];
        for (std::size_t start = 0; start < cells; ++start) {
            // `start` runs over the first cell of every line along this axis.
            if ((start / step) % n != 0) continue;
            for (std::size_t q = 0; q < n; ++q)
                f[q] = dist[start + q * step], s[q] = nearest_[start + q * step];
            transform_line(f.data(), s.data(), n, d.data(), s_out.data(), v, z);
            for (std::size_t q = 0; q < n; ++q)
                dist[start + q * step] = d[q], nearest_[start + q * step] = s_out[q];
        }
    }
    if (points.size() < kOutside16) {
        nearest16_.resize(cells);
        for (std::size_t i = 0; i < cells; ++i)
            nearest16_[i] =
                nearest_[i] == kOutside ? kOutside16 : static_cast<std::uint16_t>(nearest_[i]);
        std::vector<std::uint32_t>().swap(nearest_);
    }
}

}  // namespace makeway::verification
