#pragma once
// The project's one pi, degree factor and angle wrapping. An implementation detail shared by the
// layers (header-only, not exported, like splitmix.hpp).
#include <cmath>
#include <numbers>

namespace trn {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180;  // radians per degree: deg * kDeg, rad / kDeg

// `rad` wrapped to (-pi, pi]. fmod is exact, so angles already in range come back unchanged.
inline double wrap_angle(double rad) {
    constexpr double kTwoPi = 2 * kPi;
    double a = std::fmod(rad, kTwoPi);
    if (a <= -kPi) a += kTwoPi;
    if (a > kPi) a -= kTwoPi;
    return a;
}

}  // namespace trn
