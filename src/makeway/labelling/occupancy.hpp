#pragma once
// The multi-session occupancy map of the paper's classification step (after Thomas et al., ICRA
// 2021): every sweep's rays are traced through a voxel grid, counting per session and voxel the
// sweeps that ended a ray there (hit) and the sweeps whose rays passed through it (free). A voxel a
// session saw as a surface but another session saw through is furniture that moved (Movable); one
// the same session both hit and saw through is something moving (Dynamic); surfaces every session
// agrees on are Permanent. Counts are per sweep, not per ray, so a near surface sampled by hundreds
// of rays weighs as much as a far one.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace makeway::labelling {

/// The four classes of the paper's unsupervised classification. Values are written to files.
enum class PointClass : std::uint8_t { kGround = 0, kPermanent = 1, kMovable = 2, kDynamic = 3 };
constexpr int kNumPointClasses = 4;
std::string_view to_string(PointClass c);

struct OccupancyParams {
    double voxel_m = 0.1;
    /// Free space ends this far short of each return [m], plus range_margin of its range: a ray
    /// grazing a surface must not carve the voxels of the surface it ends on.
    double end_margin_m = 0.15;
    double range_margin = 0.02;
    double max_range_m = 40.0;  ///< longer rays are traced only this far (their end is not a hit)
    /// Movable: another session saw the voxel free in at least this many sweeps ...
    int min_free_sweeps = 2;
    /// ... and hit it in at most this share of them (grazing rays and range noise hit now and
    /// then).
    double absent_hit_ratio = 0.15;
    /// Dynamic: the point's own session saw the voxel free in at least this many sweeps and hit it
    /// in fewer than this share of them (a walker fills a voxel for a sweep or two).
    int dynamic_min_free = 3;
    double dynamic_hit_ratio = 0.5;
    std::size_t max_voxels =
        200'000'000;  ///< sessions x voxels of the grid; a larger area is refused
    std::vector<std::string> validate() const;
};

class MultiSessionOccupancy {
  public:
    /// `bounds`: the world box the sessions' points lie in (rays are clipped to it).
    MultiSessionOccupancy(const OccupancyParams& params, const Eigen::AlignedBox3d& bounds,
                          int sessions);

    /// One sweep of `session`: rays from `origin` to every point (world frame).
    void add_sweep(int session, const Eigen::Vector3d& origin,
                   const std::vector<Eigen::Vector3f>& points_world);

    struct Evidence {
        int hits = 0;  ///< sweeps with a return in the voxel
        int free = 0;  ///< sweeps with a ray through it
    };
    Evidence evidence(int session, const Eigen::Vector3d& p_world) const;
    /// Permanent, Movable or Dynamic (Ground is the ground plane's, not the map's) for a point of
    /// `session`.
    PointClass classify(int session, const Eigen::Vector3d& p_world) const;
    int sessions() const { return sessions_; }

  private:
    struct Cell {
        std::uint16_t hits = 0, free = 0;
        std::uint32_t last_hit = 0, last_free = 0;  ///< the sweep that counted last (+1; 0: none)
    };
    bool index_of(const Eigen::Vector3d& p, Eigen::Vector3i& v) const;
    std::size_t flat(const Eigen::Vector3i& v) const {
        return (static_cast<std::size_t>(v.z()) * static_cast<std::size_t>(dims_.y()) +
                static_cast<std::size_t>(v.y())) *
                   static_cast<std::size_t>(dims_.x()) +
               static_cast<std::size_t>(v.x());
    }
    Cell& cell(int session, std::size_t i) {
        return cells_[static_cast<std::size_t>(session) * voxels_ + i];
    }
    const Cell& cell(int session, std::size_t i) const {
        return cells_[static_cast<std::size_t>(session) * voxels_ + i];
    }

    OccupancyParams params_;
    Eigen::Vector3d origin_;
    Eigen::Vector3i dims_;
    std::size_t voxels_ = 0;
    int sessions_ = 0;
    std::uint32_t sweep_ = 0;
    std::vector<Cell> cells_;
};

}  // namespace makeway::labelling
