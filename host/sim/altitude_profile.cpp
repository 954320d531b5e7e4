#include "trn/sim/altitude_profile.hpp"

#include <algorithm>
#include <cmath>

#include "trn/error.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {

AltitudeProfile::AltitudeProfile(const Scenario& s) : a_m_(s.altitude_m), b_m_(s.other_altitude_m), duration_s_(s.duration_s) {
    if (!(s.other_altitude_m > 0)) return;  // constant altitude
    if (!(s.climb_s > 0) || !std::isfinite(s.climb_s)) throw Error("scenario " + s.name + ": climb_s must be > 0");
    if (!(s.duration_s > 0) || !std::isfinite(s.duration_s)) throw Error("scenario " + s.name + ": duration_s must be > 0");
    changes_ = std::max(1, static_cast<int>(std::floor((s.duration_s / s.climb_s - 1) / 2)));
    climb_s_ = std::min(s.climb_s, s.duration_s / (changes_ + 1));  // a very short flight climbs all the time
    leg_s_ = (s.duration_s - changes_ * climb_s_) / (changes_ + 1);
}

double AltitudeProfile::altitude_m(double t) const {
    if (changes_ == 0) return a_m_;
    double u = std::fmod(std::max(t, 0.0), 2 * duration_s_);
    if (u > duration_s_) u = 2 * duration_s_ - u;  // backwards after the end
    const int k = std::min(changes_, static_cast<int>(std::floor(u / (leg_s_ + climb_s_))));
    const double in_leg = u - k * (leg_s_ + climb_s_);
    const double from = k % 2 ? b_m_ : a_m_, to = k % 2 ? a_m_ : b_m_;
    if (k == changes_ || in_leg <= leg_s_) return from;
    const double f = std::min(1.0, (in_leg - leg_s_) / climb_s_);
    return from + (to - from) * (1 - std::cos(kPi * f)) / 2;
}

}  // namespace trn::sim
