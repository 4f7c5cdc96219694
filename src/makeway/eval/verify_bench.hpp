#pragma once
// The verification benchmark: simulated keyframes, ground-truth boxes corrupted the way detectors
// fail (centre, size and yaw noise; yaw flips by pi/2, pi, 3pi/2), plus false boxes on walls and
// clutter; verification with CAD models that match the objects, with models that do not, and with
// the objects' own models scaled by 0.9-1.1 per axis (similar, not identical).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "makeway/perception/ground.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::eval {

struct VerifyBenchParams {
    int scenes = 5;
    std::uint64_t seed = 0;
    double centre_sigma_m = 0.06;
    double size_sigma = 0.08;  ///< relative
    double yaw_sigma_deg = 5.0;
    double p_flip_90 = 0.2;  ///< each of +pi/2 and -pi/2
    double p_flip_180 = 0.2;
    int false_boxes_per_scene = 10;
    std::size_t min_points = 100;  ///< objects with fewer keyframe points are not scored
    verification::VerifyParams verify;
};

struct OrientationStats {
    std::size_t objects = 0;
    double yaw_within_10deg = 0.0;
    double yaw_within_30deg = 0.0;
    double median_yaw_error_deg = 0.0;
    double median_centre_error_m = 0.0;
};

struct VerifyBenchArm {  ///< one library: matched, mismatched or scaled models
    OrientationStats before;
    OrientationStats after;  ///< accepted detections at their refined pose
    double true_rejection_rate = 0.0;
    double approximate_rate =
        0.0;  ///< true boxes accepted by the approximate level (approx_e_max_m)
    double false_acceptance_rate = 0.0;
    double ms_per_object_median = 0.0;
    double ms_per_object_p99 = 0.0;
};

struct VerifyBenchResult {
    VerifyBenchArm matched;
    VerifyBenchArm mismatched;
    VerifyBenchArm scaled;
    std::size_t true_boxes = 0;
    std::size_t false_boxes = 0;
};

/// Yaw error [deg] up to the symmetry of a furniture style: chairs 2 pi, rectangular tables pi;
/// none for round tables and stools (any yaw is right).
std::optional<double> yaw_error_deg(const std::string& style, double yaw_a_rad, double yaw_b_rad);

/// One benchmark scene: a keyframe of 5 static sweeps from the scene's waypoint, ground and ceiling
/// removed, with the scene's ground truth.
struct BenchKeyframe {
    sim::Scene scene;
    std::vector<sim::ObjectModel> models;  ///< one per scene object
    Isometry3 T_world_sensor = Isometry3::Identity();
    PointCloud cloud_sensor;  ///< instance ids per point
    perception::GroundPlaneResult ground;
    double floor_z_m(const Eigen::Vector3d& p_sensor) const;  ///< the floor's height under a point
};
/// Scene k of a benchmark run with this seed (medium and dense rooms alternate, no people).
BenchKeyframe simulate_bench_keyframe(std::uint64_t seed, int k);

/// Runs the benchmark; `progress(done, total)` is called after each scene.
VerifyBenchResult run_verify_bench(const VerifyBenchParams& params,
                                   const std::function<void(int, int)>& progress = {});

}  // namespace makeway::eval
