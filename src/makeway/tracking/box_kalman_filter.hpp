#pragma once
// A 3D box Kalman filter in the style of AB3DMOT (Weng et al., IROS 2020), re-implemented from
// the published description: state [x, y, z, yaw, l, w, h, vx, vy, vz], constant velocity,
// observation of the first seven.
//
// A box with yaw theta and size (l, w) is the same box as one with yaw theta + pi/2 and size (w,
// l), and detectors trained on rotated IoU confuse the two (and theta with theta + pi). Each
// detection is therefore re-expressed as the equivalent box within pi/4 of the predicted yaw before
// the update (AB3DMOT flips the prediction by pi for the same reason), so a flipped detection does
// not turn the track. The track's heading among the four quarter turns is decided by votes: when
// most recent detections agree on another quarter turn, the state turns to it.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "makeway/common/oriented_box.hpp"

namespace makeway::tracking {

/// The motion model's noise. The defaults are furniture's (still most of the time, pushed at a
/// walk, boxes from a few centimetres of noise); traffic's are in `traffic_preset`
/// (object_map.hpp).
struct KalmanParams {
    double accel_sigma_mps2 = 0.5;  ///< white-noise acceleration (x, y, z)
    /// Position random walk [m/sqrt(s)]: variance sigma^2 dt added per prediction, for boxes that
    /// jump between frames by more than any acceleration explains. 0 by default and in the traffic
    /// presets (1 m/sqrt(s) scored no better on KITTI's training sequences: README).
    double position_sigma_mps = 0.0;
    double yaw_rate_sigma_radps = 0.5;  ///< yaw random walk
    double size_sigma_mps = 0.02;       ///< size random walk [m/s]
    double meas_position_sigma_m = 0.05;
    double meas_yaw_sigma_rad = 0.1;
    double meas_size_sigma_m = 0.05;
    double initial_velocity_sigma_mps =
        0.2;  ///< a new track's velocity: 0 +- this (traffic: unknown, metres per frame)
    int heading_votes_to_turn = 3;  ///< net votes for another quarter turn that turn the track
    std::vector<std::string> validate() const;
};

using BoxState = Eigen::Matrix<double, 10, 1>;
using BoxCovariance = Eigen::Matrix<double, 10, 10>;

class BoxKalmanFilter {
  public:
    BoxKalmanFilter(const OrientedBox& first_world, const KalmanParams& params);

    void predict(double dt_s) { predict(dt_s, params_.yaw_rate_sigma_radps); }
    /// The same with this yaw random walk instead of the parameters' (an object at rest turns
    /// less than one being pushed: ObjectMap's MotionPrior::rest_yaw_rate_sigma_radps).
    void predict(double dt_s, double yaw_rate_sigma_radps);
    /// Updates with a detection box (world frame); returns the quarter turn k (0..3) by which the
    /// detection's yaw differed from the track's (0 = agreed; 2 = flipped by pi).
    int update(const OrientedBox& detection_world, double weight = 1.0);

    /// The detection's yaw minus the track's, as the update will see it: the equivalent box within
    /// pi/4 of the track's yaw, so in [-pi/4, pi/4].
    double yaw_innovation(const OrientedBox& detection_world) const;
    /// The yaw's variance grows by this (a turn the detections agree on, outside the prediction).
    void add_yaw_variance(double variance_rad2) { P_(3, 3) += variance_rad2; }

    /// Velocity <- diag(factors) velocity, covariance alike (D P D^T): a motion prior's decay.
    void scale_velocity(const Eigen::Vector3d& factors);
    /// Horizontal velocity replaced (an estimate from outside the filter: the window fit).
    void set_planar_velocity(const Eigen::Vector2d& v_mps) { x_.segment<2>(7) = v_mps; }
    /// Velocity set to zero with the uncertainty of a new object (initial_velocity_sigma_mps) and
    /// no correlation: "at rest, as far as we know". Scaling by 0 instead would make the filter
    /// certain of rest, and a pushed chair would outrun its own track.
    void hold_at_rest();
    /// Horizontal speed clamped to max_mps (the state only: a bound, not a measurement).
    void clamp_speed(double max_mps);

    OrientedBox box() const;
    Eigen::Vector3d velocity_mps() const { return x_.tail<3>(); }
    const BoxState& state() const { return x_; }
    const BoxCovariance& covariance() const { return P_; }

  private:
    /// The quarter turn k (0..3) from the track's yaw to the detection's equivalent box within
    /// pi/4 of it, and that box's yaw minus the track's (`innovation`).
    int quarter_turn(const OrientedBox& detection_world, double& innovation) const;

    KalmanParams params_;
    BoxState x_ = BoxState::Zero();
    BoxCovariance P_ = BoxCovariance::Identity();
    std::array<double, 4> votes_{0, 0, 0, 0};  ///< decaying votes per quarter turn
};

}  // namespace makeway::tracking
