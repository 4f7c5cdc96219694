#pragma once
// A dense grid around a CAD model level storing, for every cell, the model point nearest the cell's
// centre: an exact Euclidean feature transform (Felzenszwalb and Huttenlocher's lower envelope of
// parabolas, one pass per axis, carrying the argmin) over the cells that hold model points. A
// nearest-neighbour query becomes one memory read instead of a k-d tree descent; the answer is the
// true nearest neighbour of the cell's centre, so it can differ from the query's own nearest
// neighbour by at most the cell's half diagonal.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace makeway::verification {

class ClosestPointGrid {
  public:
    static constexpr std::uint32_t kOutside = UINT32_MAX;

    ClosestPointGrid() = default;
    /// Covers the points' bounding box grown by margin_m [m] on every side with cells of cell_m
    /// [m].
    ClosestPointGrid(const std::vector<Eigen::Vector3d>& points, double cell_m, double margin_m);

    /// Index of the point nearest the centre of q's cell, or kOutside when q is off the grid
    /// (or the grid is empty).
    std::uint32_t lookup(const Eigen::Vector3d& q) const {
        const Eigen::Array3d f = (q - origin_m_).array() * inv_cell_m_;
        if (!(f >= 0.0).all() || !(f < dims_.cast<double>()).all()) return kOutside;  // also NaN
        const Eigen::Array3i c = f.cast<int>();
        return at(static_cast<std::size_t>((c.z() * dims_.y() + c.y()) * dims_.x() + c.x()));
    }

    /// The nearest of the points held by the 8 cells whose centres surround q: exact unless two
    /// surfaces meet within a cell of q. kOutside off the grid's interior.
    std::uint32_t nearest(const Eigen::Vector3d& q, const std::vector<Eigen::Vector3d>& points,
                          double* distance2) const {
        const Eigen::Array3d f = (q - origin_m_).array() * inv_cell_m_ - 0.5;
        if (!(f >= 0.0).all() || !(f < (dims_ - 1).cast<double>()).all())
            return kOutside;  // also NaN
        const Eigen::Array3i c = f.cast<int>();
        const std::size_t base =
            static_cast<std::size_t>((c.z() * dims_.y() + c.y()) * dims_.x() + c.x());
        const std::size_t dy = static_cast<std::size_t>(dims_.x()),
                          dz = dy * static_cast<std::size_t>(dims_.y());
        std::uint32_t best = kOutside;
        double best_d2 = 0.0;
        for (const std::size_t off :
             {std::size_t{0}, std::size_t{1}, dy, dy + 1, dz, dz + 1, dz + dy, dz + dy + 1}) {
            const std::uint32_t j = at(base + off);
            if (j == best) continue;
            const double d2 = (points[j] - q).squaredNorm();
            if (best == kOutside || d2 < best_d2) best = j, best_d2 = d2;
        }
        *distance2 = best_d2;
        return best;
    }

    double cell_m() const { return cell_m_; }
    Eigen::Array3i dims() const { return dims_; }
    std::size_t memory_bytes() const {
        return nearest_.size() * sizeof(std::uint32_t) + nearest16_.size() * sizeof(std::uint16_t);
    }

  private:
    static constexpr std::uint16_t kOutside16 = UINT16_MAX;
    /// The point index of cell i. The reads from this table are what a query waits for (a model's
    /// grids took 0.4-6.5 MB with 32-bit entries, more than a core's cache): 16-bit entries, when
    /// the points allow, halve that.
    std::uint32_t at(std::size_t i) const {
        if (nearest16_.empty()) return nearest_[i];
        const std::uint16_t j = nearest16_[i];
        return j == kOutside16 ? kOutside : j;
    }

    Eigen::Vector3d origin_m_ = Eigen::Vector3d::Zero();
    double cell_m_ = 1.0;
    double inv_cell_m_ = 1.0;  ///< a multiplication per query instead of a division
    Eigen::Array3i dims_ = Eigen::Array3i::Zero();
    std::vector<std::uint32_t> nearest_;    ///< per cell, 32-bit (empty when nearest16_ is used)
    std::vector<std::uint16_t> nearest16_;  ///< the same with fewer than 65,535 points
};

}  // namespace makeway::verification
