#pragma once
// The shape networks' benchmark (`makeway bench shape`): rooms the networks never saw (held-out
// seeds, all styles they were trained on) and rooms furnished only with the styles left out of
// training. Pose from F_n alone per view (objects seen from at least min_points returns);
// completion per object from all its views fused, in the object's true canonical frame (shape
// quality apart from pose error), scored against the true mesh for the partial cloud alone, F_0
// fitted alone and F_1, by Chamfer-L1 [m] and volumetric IoU on the canonical grid.
#include <functional>
#include <string>
#include <vector>

#include "makeway/eval/shape_dataset.hpp"
#include "makeway/shape/shape_completion.hpp"

namespace makeway::eval {

struct ShapeBenchParams {
    int scenes = 6;
    std::uint64_t seed = 1000;  ///< held out: training uses other seeds
    std::vector<std::string>
        left_out_styles;  ///< the styles training excluded; empty: no second set
    std::size_t min_points = 100;
    int fit_iterations = 60;         ///< F_0's code fit
    int showcase = 4;                ///< completed shapes kept per class for pictures
    shape::RobustSolveParams solve;  ///< F_n's 7-DoF solve
    bool completion = true;          ///< false: pose only
};

struct PoseStats {
    std::size_t views = 0;
    std::size_t yaw_scored = 0;      ///< views whose style has a yaw to get right
    double yaw_within_10deg = 0.0;   ///< share of yaw_scored
    double centre_within_5cm = 0.0;  ///< share of views (box centre, horizontal)
    double median_yaw_error_deg = 0.0;
    double median_centre_error_m = 0.0;
    std::size_t failed = 0;  ///< no pose from the solve (counted as misses)
};

struct CompletionStats {
    std::size_t objects = 0;
    double chamfer_partial_m = 0.0, chamfer_prior_m = 0.0, chamfer_completed_m = 0.0;  ///< means
    double iou_partial = 0.0, iou_prior = 0.0, iou_completed = 0.0;                    ///< means
};

struct ShapeBenchSet {
    std::string name;
    PoseStats pose[2];  ///< chair, table
    CompletionStats completion[2];
};

struct ShowcaseShape {
    std::string name;                      ///< class, style
    std::vector<Eigen::Vector3d> partial;  ///< canonical
    TriangleMesh prior, completed, truth;  ///< canonical
};

struct ShapeBenchResult {
    std::vector<ShapeBenchSet> sets;
    double fn_ms_median = 0.0, fn_ms_p90 = 0.0;  ///< F_n + robust solve, one view
    double f1_update_ms_median = 0.0;            ///< TSDF integration of a view + F_1's encoder
    double f1_mesh_ms_median = 0.0;              ///< F_1 on the whole grid + isosurface
    double f0_fit_ms_median = 0.0;
    std::vector<ShowcaseShape> showcase;
};

/// `progress(what, done, total)`.
ShapeBenchResult run_shape_bench(
    const shape::ShapeModel& model, const ShapeBenchParams& params,
    const std::function<void(const std::string&, int, int)>& progress = {});

}  // namespace makeway::eval
