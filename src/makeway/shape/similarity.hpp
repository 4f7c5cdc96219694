#pragma once
// The 7-DoF similarity of the supplementary's init loss: canonical coordinates v (predicted by F_n
// for each observed point p) and their weights w give
//     argmin_{s, R, t} sum_i w_i || p_i - (s R v_i + t) ||^2,
// solved in closed form (Umeyama 1991, weighted): centre both sets on their weighted centroids, R
// from the SVD of the weighted cross-covariance (a reflection turned into the nearest rotation),
// s = tr(D S) / sum w |v - v_bar|^2, t = p_bar - s R v_bar. Objects stand on the floor, so the
// upright option keeps R a turn about z: yaw = atan2 of the covariance's antisymmetric and
// symmetric xy parts, the same least squares restricted to yaw.
//
// The robust solve can wrap it: minimal samples (3 points, 2 when upright) drawn with a seed score
// the weighted points whose residual is under the inlier distance, the best hypothesis is refined
// by the weighted solve on its inliers, twice. It recovers the similarity as long as the inliers
// outnumber what the sampling can miss: 50 % outliers at the default 200 hypotheses (tested).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

namespace makeway::shape {

struct Similarity3 {
    double scale = 1.0;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Vector3d apply(const Eigen::Vector3d& v) const {
        return scale * (rotation * v) + translation;
    }
    /// The canonical point of an observed point.
    Eigen::Vector3d inverse_apply(const Eigen::Vector3d& p) const {
        return rotation.transpose() * (p - translation) / scale;
    }
    double yaw_rad() const;
};

/// Weighted least squares over the pairs (v_i -> p_i). nullopt when fewer than 3 pairs (2 upright)
/// carry weight, the sizes differ, a weight is negative or not finite, or the canonical points
/// are degenerate (all on one point; on a line when not upright).
std::optional<Similarity3> solve_similarity(const std::vector<Eigen::Vector3d>& canonical,
                                            const std::vector<Eigen::Vector3d>& observed,
                                            const std::vector<double>& weights, bool upright);

struct RobustSolveParams {
    bool upright = true;
    /// 0 (default): the weighted least squares alone, every pair an inlier: F_n is trained end to
    /// end through that solve, and its spread of errors defeats a residual threshold (measured:
    /// median yaw error 10 deg with it, 78 deg with 200 hypotheses at 5 cm). Sampling is for
    /// correspondences that are exact or wrong.
    int hypotheses = 0;
    double inlier_distance =
        0.05;  ///< residual [units of `observed`] under which a pair supports a hypothesis
    double min_scale = 0.05, max_scale = 20.0;  ///< hypotheses outside are discarded
    std::uint64_t seed = 0;
};

struct RobustSolveResult {
    Similarity3 similarity;
    std::vector<bool> inlier;  ///< per pair, for the final refinement
    std::size_t inliers = 0;
};

/// Sample-and-refine solve (above). nullopt when no hypothesis finds enough support (3 pairs).
std::optional<RobustSolveResult> solve_similarity_robust(
    const std::vector<Eigen::Vector3d>& canonical, const std::vector<Eigen::Vector3d>& observed,
    const std::vector<double>& weights, const RobustSolveParams& params = {});

}  // namespace makeway::shape
