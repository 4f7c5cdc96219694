#pragma once
// Angle helpers [rad]. Header-only: used in every inner loop. C++17-clean (the ROS 1 files,
// whose message headers do not compile as C++20, include it).
#include <cmath>

namespace makeway {

constexpr double kPi = 3.14159265358979323846;  // std::numbers::pi, which C++17 lacks

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
