#pragma once
// Geometric verification of detections (paper, "Geometry Verification"): the scan segment inside
// each (slightly enlarged) box is aligned to every CAD model of the detected class, starting from
// the best of the four yaw candidates theta + k pi/2; the best fit is kept, rejected when its
// residual exceeds e_max, and otherwise given p_exist = 1 - (e - e_min) / (2 (e_max - e_min))
// (eq. 2, clamped to [0.5, 1]). Beyond the paper, a second level for CAD models that are close
// but not exact (approx_e_max_m): such a fit places the box, the network's score stays.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/verification/icp.hpp"
#include "makeway/verification/shape_prior.hpp"

namespace makeway::verification {

struct VerifyParams {
    IcpParams icp;
    double box_margin_m = 0.15;    ///< the box is grown by this on every side to cut the segment
    int candidate_iterations = 4;  ///< coarse Gauss-Newton steps per yaw candidate before ranking
    double max_size_mismatch =
        0.3;             ///< |log(model / detected size)| per dimension for a model to be tried
    int max_models = 4;  ///< at most this many models (closest in size) are tried
    int refined_candidates = 4;  ///< best-ranked candidates aligned fully; the lowest residual wins
    /// Rejected when another orientation's residual is within this fraction of the winner's (the
    /// paper keeps only detections with a confident orientation). Off by default: 0.1 lifts the
    /// accepted yaw within 10 deg from 94 to 95 % but rejects 5 % more true objects, and the
    /// navigation benchmark's risk time rose with it (see README).
    double min_yaw_margin = 0.0;
    double e_min_m = 0.01;   ///< residual at or below which p_exist = 1
    double e_max_m = 0.035;  ///< residual above which the detection is rejected ...
    /// ... unless it is at most this (> e_max_m; 0: off): the model fits approximately (a CAD
    /// library of similar, not identical, furniture, as real ones are). Such a fit gives the
    /// yaw (the network's box, turned to it: the model's extent is not the object's), and its
    /// residual says nothing about existence: the detection keeps the network's score as p_exist
    /// (VerifiedDetection::approximate). Off by default: on bench verify it accepts 8-10 % more
    /// true boxes and 11 % more false boxes on walls at 0.05 (README).
    double approx_e_max_m = 0.0;
    /// A detection no CAD model fits (rejected: too few points, no model of its class, a residual
    /// above the bounds) stays what the network says, its box and its score, instead of being
    /// dropped: a library of similar furniture, not the very models, rejects many true objects.
    /// Off by default: on eval-detection it lifts the map's mAP@0.25 from 0.909 to 0.938 with the
    /// scenes' own models and from 0.825 to 0.926 with other dimensions, but on bench nav --scenes
    /// 200 ours' avoidable risk rose 15 % (194 successes instead of 193; README).
    bool keep_unfitted = false;
    /// e_max for a learned shape prior's completed mesh (coarser than a CAD model: its own bound).
    double shape_e_max_m = 0.035;
    std::size_t min_points = 15;  ///< fewer segment points: rejected without fitting
    /// A detection of an object verified before (the object map's track) is re-verified from that
    /// fit with one ICP, accepted when its residual ends within this of the fit's (and within
    /// e_max); else, or with 0, verified from scratch (every model, every yaw candidate). Off by
    /// default: 0.005 cut the keyframe chain by a quarter to a third but lost 7 of 200 benchmark
    /// runs (README, issue 31).
    double reseed_tolerance_m = 0.0;
    double reseed_radius_m =
        0.3;  ///< the detection's centre this close to the fit's (world frame) ...
    double reseed_max_age_s = 5.0;  ///< ... and the fit at most this old
    /// verify_detections: 1 serial; > 1 that many threads over detections (each is independent).
    int num_threads = 2;
    std::vector<std::string> validate() const;
};

struct VerifiedDetection {
    Detection detection;  ///< as given
    bool accepted = false;
    std::string reason;  ///< why rejected
    Isometry3 T_sensor_object = Isometry3::Identity();
    OrientedBox box_sensor;  ///< the CAD model's extent at the refined pose (approximate: the
                             ///< detection's box at its yaw)
    double residual_m = 0.0;
    /// How much worse the best rival orientation fits: its residual / the winner's - 1 (infinite
    /// when no refined candidate was a rival).
    double yaw_margin = 0.0;
    int iterations = 0;
    bool converged = false;
    double p_exist = 0.0;
    std::string model;
    std::size_t segment_points = 0;
    bool from_seed = false;    ///< accepted by one ICP from an earlier fit (VerifySeed)
    bool approximate = false;  ///< accepted with e_max_m < residual <= approx_e_max_m: p_exist is
                               ///< the network's score
    /// Accepted against a shape prior's mesh (model == kCompletedShapeModel): that estimate, whose
    /// mesh T_sensor_object above places (its own T_sensor_object is the prior's, before ICP).
    std::optional<ShapePrior::Estimate> shape;
};

/// A fit found before for the object a detection shows: where to re-verify it from.
struct VerifySeed {
    const CadModel* model = nullptr;
    Pose4 pose;  ///< that fit's T_sensor_object, moved into this keyframe's sensor frame
    double residual_m = 0.0;  ///< that fit's residual
};

/// The segment: points of the cloud inside the detection box grown by margin.
std::vector<Eigen::Vector3d> segment_points(const PointCloud& cloud_sensor, const OrientedBox& box,
                                            double margin_m);

/// segment_points() of every box, cut through floor-plane buckets of the cloud built once: the same
/// points in the same order, without reading the whole cloud once per box.
std::vector<std::vector<Eigen::Vector3d>> segments_of(const PointCloud& cloud_sensor,
                                                      const std::vector<OrientedBox>& boxes,
                                                      double margin_m);

/// p_exist of eq. (2) for an accepted residual.
double existence_probability(double residual_m, double e_min_m, double e_max_m);

/// `floor_z_m`: the floor's height in the sensor frame under the object (from the ground plane),
/// where the object's origin sits; without it the detection box's bottom is used.
/// With a shape prior, a detection no CAD model fits is verified against the prior's model of it
/// instead (a library of that one completed mesh, from the prior's pose): accepted when that fit's
/// residual is, with the model named "completed shape".
/// With a seed, one ICP from it first (accepted as above), the full search only when that fails
/// (params.reseed_tolerance_m > 0; never with min_yaw_margin > 0, which needs the rivals).
VerifiedDetection verify_detection(const PointCloud& cloud_sensor, const Detection& detection,
                                   const CadLibrary& library, const VerifyParams& params,
                                   std::optional<double> floor_z_m = std::nullopt,
                                   const ShapePrior* prior = nullptr,
                                   const VerifySeed* seed = nullptr);

/// verify_detection() of every detection, in order; `floor_z_at(x_m, y_m)` gives the floor height
/// under a detection (none: the box bottom); `seeds`: empty, or one per detection.
std::vector<VerifiedDetection> verify_detections(
    const PointCloud& cloud_sensor, const std::vector<Detection>& detections,
    const CadLibrary& library, const VerifyParams& params,
    const std::function<std::optional<double>(double, double)>& floor_z_at = {},
    const ShapePrior* prior = nullptr, const std::vector<std::optional<VerifySeed>>& seeds = {});

/// Which score an accepted detection carries on.
enum class ScoreFrom {
    kExistence,  ///< p_exist (eq. 2): the per-frame existence evidence the object map fuses
    kDetector,   ///< the network's confidence
};

/// The accepted detections with the CAD model's box at the refined pose, in order (the i-th is
/// the i-th accepted one of `verified`); with keep_unfitted (VerifyParams) the rejected ones after
/// them, as the network gave them: its box and its score.
std::vector<Detection> accepted_detections(const std::vector<VerifiedDetection>& verified,
                                           ScoreFrom score = ScoreFrom::kExistence,
                                           bool keep_unfitted = false);

}  // namespace makeway::verification
