#pragma once
// LiDAR odometry fused with wheel odometry, one sweep at a time (the paper's front end).
//
// For every sweep, in the spirit of KISS-ICP with two changes for an indoor ground robot:
//   1. prediction: the wheel odometry's motion over the sweep (constant velocity without it);
//   2. de-skewing: each point moved to the sweep's end with the predicted motion at its own time;
//   3. registration against the local voxel map, planar (x, y, yaw: the robot drives on a floor),
//      point-to-plane where the map is flat and point-to-point elsewhere, Geman-McClure weights
//      with an adaptive correspondence threshold (people and pushed chairs are outliers), and the
//      wheel prediction as a Gaussian prior in the same least squares:
//
//          min_xi  sum_i w_i r_i(xi)^2 / sigma_r^2  +  (xi - xi_wheel)^T Lambda_wheel (xi -
//          xi_wheel)
//
//      Where the geometry constrains a direction (thousands of wall points) the LiDAR term wins;
//      along a featureless corridor the point-to-plane term is flat and the wheel prior holds the
//      pose instead of the registration sliding or sticking;
//   4. the registered sweep added to the map; voxels far from the robot dropped.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/odometry/voxel_map.hpp"

namespace makeway::odometry {

struct OdometryParams {
    VoxelMapParams map;
    double source_voxel_m = 0.3;  ///< registration uses one point per voxel of this size
    double insert_voxel_m = 0.1;  ///< the map receives one point per voxel of this size
    double min_range_m = 0.5;     ///< closer returns (the robot, a person at the sensor) unused
    double max_range_m = 40.0;
    double min_height_m = 0.15;  ///< above the base: the floor constrains no planar motion
    double map_radius_m = 40.0;  ///< voxels farther from the robot are dropped
    int max_iterations = 15;
    double convergence_m = 1e-4;  ///< stop when a step moves less (rotation at 1 m counted alike)
    double initial_threshold_m = 0.5;  ///< correspondence distance until the motion model is learnt
    double min_threshold_m = 0.1, max_threshold_m = 1.0;
    double residual_sigma_m = 0.03;  ///< one correspondence's noise, against the wheel prior
    /// The wheel prediction's sigma over one sweep: a floor plus a share of the distance driven /
    /// the angle turned (the Jackal's odometry drifts about 2 cm per metre).
    double wheel_sigma_m = 0.005, wheel_sigma_per_m = 0.05;
    double wheel_sigma_rad = 0.002, wheel_sigma_per_rad = 0.05;
    bool deskew = true;
    int threads = 2;  ///< the correspondence search's threads (1: the caller's alone); the
                      ///< same poses for any count
    std::vector<std::string> validate() const;
};

struct OdometryResult {
    Isometry3 T_world_sensor_start = Isometry3::Identity();
    Isometry3 T_world_sensor_end = Isometry3::Identity();
    Pose2 pose;  ///< the base at the sweep's end
    int iterations = 0;
    std::size_t source_points = 0, correspondences = 0;
    double threshold_m = 0.0;  ///< the correspondence distance used
    /// Smallest / largest eigenvalue of the LiDAR term's information (x, y, yaw at 1 m): near zero
    /// along a featureless corridor, where the wheel prior decided.
    double constraint_ratio = 0.0;
};

class LidarOdometry {
  public:
    /// Throws std::invalid_argument listing every problem of `params`.
    LidarOdometry(const OdometryParams& params, const Isometry3& T_base_sensor,
                  const Pose2& start_pose);

    /// One sweep: points in the sensor frame at their own firing time (`time_s` since `stamp_s`;
    /// without it the sweep is instantaneous), wheel odometry at the sweep's start and end when the
    /// robot has it.
    OdometryResult register_sweep(const PointCloud& points_sensor, double stamp_s,
                                  double duration_s, const std::optional<Pose2>& wheel_start,
                                  const std::optional<Pose2>& wheel_end);

    const VoxelMap& map() const { return map_; }
    const Pose2& pose() const { return pose_; }

  private:
    OdometryParams params_;
    Isometry3 T_base_sensor_;
    Pose2 pose_;
    VoxelMap map_;
    std::optional<Pose2> last_wheel_end_;
    Pose2 last_motion_;               ///< the base's motion over the last sweep (its own frame)
    std::vector<double> deviations_;  ///< |estimate - prediction| per sweep: the adaptive threshold
    bool first_ = true;
    struct Threads;                     ///< params_.threads > 1: the searches' TBB arena
    std::shared_ptr<Threads> threads_;  ///< shared by copies (an arena is not copyable)
};

}  // namespace makeway::odometry
