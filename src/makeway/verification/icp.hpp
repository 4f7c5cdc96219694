#pragma once
// The paper's customised ICP (eq. 1): point-to-plane residuals against a CAD model's surface
// normals, optimising yaw and translation only (objects stand on the ground), Cauchy robust loss,
// Gauss-Newton, coarse-to-fine over the model's voxel levels.
#include <string>
#include <vector>

#include "makeway/common/voxel_thin.hpp"
#include "makeway/verification/cad_library.hpp"

namespace makeway::verification {

/// T_sensor_object restricted to a translation and a rotation about z.
struct Pose4 {
    Eigen::Vector3d t_m = Eigen::Vector3d::Zero();
    double yaw_rad = 0.0;
    Isometry3 matrix() const;
};

struct IcpParams {
    std::vector<int> iterations{15, 10, 10};  ///< per level, coarse to fine
    std::vector<double> max_correspondence_m{0.30, 0.15, 0.08};
    double cauchy_scale_m =
        0.03;  ///< c in rho(r) = c^2/2 log(1 + (r/c)^2); at least the level's voxel
    double convergence_m = 5e-4;  ///< stop a level when the step is smaller
    double convergence_rad = 5e-4;
    /// Objects stand on the ground, and a LiDAR at seat height sees chairs' vertical parts (legs,
    /// backs) far better than their horizontal ones, so z is weakly observed: a prior keeps it at
    /// the initial value (the detection's floor contact), weighted relative to the correspondences.
    double z_prior_weight = 0.2;
    double residual_keep_fraction = 0.8;  ///< the final residual ignores the worst 20 % of points
    std::vector<std::string> validate(std::size_t levels) const;
};

struct IcpResult {
    Pose4 pose;
    double residual_m = 0.0;  ///< truncated RMS point-to-plane distance at the finest level
    int iterations = 0;
    bool converged = false;
};

/// Point-to-plane residual of the segment against the model at `level` for a pose: the RMS over
/// the best keep_fraction of per-point distances, each truncated at max_correspondence_m (points
/// without a model surface nearby count fully). The quantity the yaw candidates and the
/// rejection test compare.
double geometric_residual(const std::vector<Eigen::Vector3d>& segment_sensor, const CadModel& model,
                          int level, const Pose4& pose, double max_correspondence_m,
                          double keep_fraction = 1.0);

/// A scan segment thinned to one point per voxel of every level of a library (accumulated
/// keyframes repeat surfaces five times over); computed once and shared by every candidate.
struct LevelledSegment {
    std::vector<std::vector<Eigen::Vector3d>> per_level_sensor;  ///< coarse to fine
};
LevelledSegment thin_to_levels(const std::vector<Eigen::Vector3d>& segment_sensor,
                               const CadModel& model);

/// Whether align() ends with the residual (IcpResult::residual_m), a pass of nearest-point queries
/// over the last level's points. Verification's candidates are ranked on residuals of their own
/// and skip it (a tenth of a detection's queries).
enum class FinalResidual { kCompute, kSkip };

/// Gauss-Newton with Cauchy weights at levels [first_level, last_level] (inclusive; -1: finest).
/// The segment must have been thinned for a model with the same voxel sizes. With
/// FinalResidual::kSkip, residual_m is NaN.
IcpResult align(const LevelledSegment& segment, const CadModel& model, const Pose4& initial,
                const IcpParams& params, int first_level = 0, int last_level = -1,
                FinalResidual final_residual = FinalResidual::kCompute);
/// The same, thinning the segment first.
IcpResult align(const std::vector<Eigen::Vector3d>& segment_sensor, const CadModel& model,
                const Pose4& initial, const IcpParams& params, int first_level = 0,
                int last_level = -1);

}  // namespace makeway::verification
