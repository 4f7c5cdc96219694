#pragma once
// Affordance zones learned from how the furniture of one building moves (issue 36), in place of the
// paper's hand-drawn shapes (affordance.hpp). A class's zone is a density over where an object's
// footprint goes between two observations: weighted motions (dx, dy, dyaw) in the object's frame
// at the earlier observation, each moving the object's own footprint, smoothed by a Gaussian
// kernel of `kernel_m` across the footprint's edges:
//
//   c_learned(q) = sum_k w_k Phi((l/2 - |x_k|) / s) Phi((w/2 - |y_k|) / s) / sum_k w_k,
//   (x_k, y_k) = R(-dyaw_k) (q - (dx_k, dy_k)),
//
// the probability that point q (object frame) lies under the footprint next time. The hand-drawn
// zone is the prior, as a coverage of its own (tau^u for the paper's zone coordinate u: 1 on the
// object, tau = coverage_threshold on its boundary, 0 outside), and the two are blended by the
// amount of evidence:
//
//   c(q) = (n c_learned(q) + n0 c_prior(q)) / (n + n0),   n = observations, n0 = prior_strength,
//
// so a class seen a few times keeps nearly the paper's shape, and with n = 0 the zone and its costs
// are exactly the paper's. The zone is where c >= tau; its coordinate u = ln c / ln tau (0 on the
// object, 1 on the boundary) drives the same cost profile as the hand-drawn zones. Logarithmic,
// because coverages span decades: with u linear in c, most of a zone (c of a few per cent) would
// cost nearly the edge cost and steer the robot hardly at all.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/object_estimate.hpp"

namespace makeway::costmap {

/// Motions farther than this are not a zone's (a zones file with one is refused; learning leaves
/// them out): a zone is where furniture goes next to where it stands, and it bounds the rasters.
constexpr double kMaxZoneMotion_m = 5.0;

/// One motion between two observations of an object, in its frame at the earlier one.
struct ZoneMotion {
    double dx_m = 0.0, dy_m = 0.0;  ///< forward (the object's +x) and left
    double dyaw_rad = 0.0;
    double weight = 1.0;
};

/// The learned zone of one class.
struct ClassZone {
    double observations = 0.0;        ///< n: observed motions behind `motions`
    std::vector<ZoneMotion> motions;  ///< weighted (binned) motions; weights need not sum to 1
    /// The median footprint (length, width) of the observed objects, for pictures and the
    /// benchmark; zero when unknown. Each object's zone uses its own footprint.
    Eigen::Vector2d typical_size_m = Eigen::Vector2d::Zero();
};

/// Rasters of c_learned per class and footprint (learned_zone.cpp), so that a costmap rewriting
/// zones every keyframe does not sum every motion for every cell.
class CoverageCache;

struct LearnedZones {
    double kernel_m = 0.05;            ///< s: smoothing across the footprint's edges (<= 0.2)
    double coverage_threshold = 0.03;  ///< the zone: where the footprint goes this often
    double prior_strength = 10.0;      ///< n0: pseudo-observations of the hand-drawn zone
    std::optional<ClassZone> chair;    ///< none: the hand-drawn zone
    std::optional<ClassZone> table;
    std::vector<std::string> validate() const;

    const ClassZone* of(ObjectClass cls) const {
        const std::optional<ClassZone>& z = cls == ObjectClass::kChair ? chair : table;
        return z ? &*z : nullptr;
    }

    /// c_learned of `cls` (which must have a zone) at q_object for footprint half extents half_m,
    /// from a raster of 2 cm cells computed once per class and footprint (half extents rounded to
    /// 5 mm), bilinear between cells: within 0.01 of learned_coverage(). Thread-safe. The zones
    /// must not be changed once this was called.
    double coverage(ObjectClass cls, const Eigen::Vector2d& half_m,
                    const Eigen::Vector2d& q_object_m) const;

  private:
    /// A copy of the zones starts with an empty cache (its zones may be changed before use).
    struct FreshCache {
        FreshCache();
        FreshCache(const FreshCache&) : FreshCache() {}
        FreshCache& operator=(const FreshCache&) {
            cache = FreshCache().cache;
            return *this;
        }
        std::shared_ptr<CoverageCache> cache;  ///< never null (no moves: a move copies)
    };
    FreshCache cache_;
};

/// c_learned at q_object for an object of footprint half extents `half_m` (no prior).
double learned_coverage(const ClassZone& zone, double kernel_m, const Eigen::Vector2d& half_m,
                        const Eigen::Vector2d& q_object_m);

/// How far from the object's centre c_learned can be non-negligible (the farthest motion plus the
/// footprint's half diagonal plus 4 kernels) [m].
double learned_reach_m(const ClassZone& zone, double kernel_m, const Eigen::Vector2d& half_m);

}  // namespace makeway::costmap
