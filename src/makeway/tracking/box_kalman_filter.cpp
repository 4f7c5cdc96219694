#include "makeway/tracking/box_kalman_filter.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "makeway/common/angles.hpp"
#include "makeway/tracking/param_tables.hpp"

namespace makeway::tracking {

std::vector<std::string> KalmanParams::validate() const { return kalman_table().problems(*this); }

BoxKalmanFilter::BoxKalmanFilter(const OrientedBox& b, const KalmanParams& params)
    : params_(params) {
    x_ << b.centre_m, b.yaw_rad, b.size_m, Eigen::Vector3d::Zero();
    P_.setZero();
    const double sp = params.meas_position_sigma_m, sy = params.meas_yaw_sigma_rad,
                 ss = params.meas_size_sigma_m, sv = params.initial_velocity_sigma_mps;
    P_.diagonal() << sp * sp, sp * sp, sp * sp, sy * sy, ss * ss, ss * ss, ss * ss, sv * sv,
        sv * sv, sv * sv;
}

void BoxKalmanFilter::predict(double dt, double yaw_rate_sigma_radps) {
    dt = std::max(0.0, dt);
    // x' = F x and P' = F P F^T with F = I + dt (position <- velocity), written out: F only adds
    // velocity rows/columns to position ones.
    x_.head<3>() += dt * x_.tail<3>();
    x_[3] = wrap_angle(x_[3]);
    for (int a = 0; a < 3; ++a) P_.row(a) += dt * P_.row(7 + a);
    for (int a = 0; a < 3; ++a) P_.col(a) += dt * P_.col(7 + a);
    const double qa = params_.accel_sigma_mps2 * params_.accel_sigma_mps2, dt2 = dt * dt;
    for (int a = 0; a < 3; ++a) {  // discrete white-noise acceleration per axis
        P_(a, a) += qa * dt2 * dt2 / 4;
        P_(a, 7 + a) += qa * dt2 * dt / 2;
        P_(7 + a, a) += qa * dt2 * dt / 2;
        P_(7 + a, 7 + a) += qa * dt2;
    }
    const double qp =
        params_.position_sigma_mps * params_.position_sigma_mps * dt;  // position random walk
    for (int a = 0; a < 3; ++a) P_(a, a) += qp;
    P_(3, 3) += yaw_rate_sigma_radps * yaw_rate_sigma_radps * dt2;
    for (int a = 4; a < 7; ++a) P_(a, a) += params_.size_sigma_mps * params_.size_sigma_mps * dt2;
}

int BoxKalmanFilter::quarter_turn(const OrientedBox& det, double& innovation) const {
    // The detection as the equivalent box within pi/4 of the predicted yaw.
    const double d = angle_diff(det.yaw_rad, x_[3]);  // det - state, in (-pi, pi]
    const int k = static_cast<int>(std::lround(d / (kPi / 2))) & 3;
    innovation = wrap_angle(d - k * kPi / 2);
    return k;
}

double BoxKalmanFilter::yaw_innovation(const OrientedBox& det) const {
    double innovation = 0.0;
    quarter_turn(det, innovation);
    return innovation;
}

int BoxKalmanFilter::update(const OrientedBox& det, double weight) {
    double dyaw = 0.0;
    const int k = quarter_turn(det, dyaw);
    Eigen::Vector3d size = det.size_m;
    if (k % 2 == 1) std::swap(size.x(), size.y());
    // Heading votes: decayed, so the track follows a persistent turn but not single flips.
    for (double& v : votes_) v *= 0.9;
    votes_[static_cast<std::size_t>(k)] += weight;
    const auto best =
        static_cast<int>(std::max_element(votes_.begin(), votes_.end()) - votes_.begin());
    if (best != 0 &&
        votes_[static_cast<std::size_t>(best)] - votes_[0] >= params_.heading_votes_to_turn) {
        x_[3] = wrap_angle(x_[3] + best * kPi /
                                       2);  // turn the track to the quarter the detections agree on
        if (best % 2 == 1) std::swap(x_[4], x_[5]), std::swap(P_(4, 4), P_(5, 5));
        std::array<double, 4> turned{};
        for (int j = 0; j < 4; ++j)
            turned[static_cast<std::size_t>((j - best + 4) & 3)] =
                votes_[static_cast<std::size_t>(j)];
        votes_ = turned;
        return update(det, 0.0);
    }
    Eigen::Matrix<double, 7, 1> innovation;
    innovation << det.centre_m - x_.head<3>(), dyaw, size - x_.segment<3>(4);
    // H selects the first 7 states: H P = P's top rows, H P H^T its top-left block.
    Eigen::Matrix<double, 7, 1> r;
    const double sp = params_.meas_position_sigma_m, sy = params_.meas_yaw_sigma_rad,
                 ss = params_.meas_size_sigma_m;
    r << sp * sp, sp * sp, sp * sp, sy * sy, ss * ss, ss * ss, ss * ss;
    Eigen::Matrix<double, 7, 7> S = P_.topLeftCorner<7, 7>();
    S.diagonal() += r;
    const Eigen::Matrix<double, 10, 7> K =
        S.llt().solve(P_.topRows<7>()).transpose();  // P H^T S^-1 (S, P symmetric)
    x_ += K * innovation;
    x_[3] = wrap_angle(x_[3]);
    x_.segment<3>(4) = x_.segment<3>(4).cwiseMax(0.01);
    P_ -= K * P_.topRows<7>();
    P_ = 0.5 * (P_ + P_.transpose()).eval();  // keep it symmetric
    return k;
}

void BoxKalmanFilter::scale_velocity(const Eigen::Vector3d& f) {
    for (int a = 0; a < 3; ++a) {
        x_[7 + a] *= f[a];
        P_.row(7 + a) *= f[a];
        P_.col(7 + a) *= f[a];
    }
}

void BoxKalmanFilter::hold_at_rest() {
    x_.tail<3>().setZero();
    P_.bottomRows<3>().setZero();
    P_.rightCols<3>().setZero();
    const double sv = params_.initial_velocity_sigma_mps;
    P_.bottomRightCorner<3, 3>().diagonal().setConstant(sv * sv);
}

void BoxKalmanFilter::clamp_speed(double max_mps) {
    const double speed = x_.segment<2>(7).norm();
    if (speed > max_mps) x_.segment<2>(7) *= max_mps / speed;
}

OrientedBox BoxKalmanFilter::box() const {
    return OrientedBox{x_.head<3>(), x_.segment<3>(4), x_[3]};
}

}  // namespace makeway::tracking
