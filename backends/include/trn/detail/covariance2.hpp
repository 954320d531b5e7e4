#pragma once
// A 2x2 position covariance's worst axis: the square root of its largest eigenvalue, one standard
// deviation along the axis the position is least sure of (what an autopilot takes as eph /
// horiz_accuracy). Shared by the Localizer's estimate and the MAVLink encoder (header-only, not
// exported, like angles.hpp).
#include <algorithm>
#include <cmath>

namespace trn {

// cov = [a c; c b] in any one pair of axes (north/east, or x/y: the eigenvalues do not depend on
// which).
inline double largest_sigma(double a, double c, double b) {
    const double half_trace = (a + b) / 2, d = (a - b) / 2;
    return std::sqrt(std::max(0.0, half_trace + std::sqrt(d * d + c * c)));
}

}  // namespace trn
