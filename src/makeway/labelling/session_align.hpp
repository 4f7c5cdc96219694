#pragma once
// Step one of the annotation: every session in the first session's frame. Each session's own
// odometry gives its map; the map is then aligned to the first session's map by planar
// point-to-plane ICP (x, y, yaw: the robot drives on one floor) with a Cauchy loss, so the walls
// and other permanent surfaces pull and the furniture that moved between sessions does not.
#include <string>
#include <vector>

#include "makeway/common/transforms.hpp"
#include "makeway/odometry/voxel_map.hpp"

namespace makeway::labelling {

struct SessionAlignParams {
    double voxel_m = 0.1;  ///< the moving map is thinned to one point per voxel
    int iterations = 30;
    std::vector<double> max_distance_m{0.5, 0.25,
                                       0.1};  ///< correspondence distance, shrinking per stage
    double cauchy_scale_m = 0.05;
    double inlier_m = 0.05;  ///< matches closer than this make the reported residual
    double convergence_m = 1e-4;
    std::vector<std::string> validate() const;
};

struct SessionAlignment {
    Isometry3 T_reference_session =
        Isometry3::Identity();     ///< maps the session's world into the reference's
    double residual_m = 0.0;       ///< RMS point-to-plane distance of the inliers after alignment
    double inlier_fraction = 0.0;  ///< share of the session's map within inlier_m of the reference
    double correction_m = 0.0,
           correction_deg = 0.0;  ///< size of the correction to the odometry's frame
    int iterations = 0;
};

/// `session_map`: the session's points in its own world frame (its odometry from its start pose);
/// `initial`: the guess (identity when sessions start at known poses of the same frame).
SessionAlignment align_session(const odometry::VoxelMap& reference,
                               const std::vector<Eigen::Vector3d>& session_map,
                               const SessionAlignParams& params,
                               const Isometry3& initial = Isometry3::Identity());

}  // namespace makeway::labelling
