#pragma once
// Angle helpers [rad]. Header-only: used in every inner loop.
#include <cmath>
#include <numbers>

namespace makeway {

constexpr double kPi = std::numbers::pi;

constexpr double deg_to_rad(double deg) { return deg * kPi / 180.0; }
constexpr double rad_to_deg(double rad) { return rad * 180.0 / kPi; }

/// Wraps an angle into [-pi, pi).
inline double wrap_angle(double angle_rad) {
    double a = std::fmod(angle_rad + kPi, 2.0 * kPi);
    if (a < 0.0) a += 2.0 * kPi;
    return a - kPi;
}

/// Signed smallest difference a - b, in [-pi, pi).
inline double angle_diff(double a_rad, double b_rad) { return wrap_angle(a_rad - b_rad); }

}  // namespace makeway
