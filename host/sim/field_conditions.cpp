#include "trn/sim/field_conditions.hpp"

#include <algorithm>
#include <cmath>

#include "random.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {

FieldConditions::FieldConditions(const Realism& realism, double nominal_altitude_m, double first_course_rad, std::uint64_t seed)
    : realism_(realism), nominal_altitude_m_(nominal_altitude_m) {
    realism_.validate();
    const std::uint64_t h = detail::hash(seed, 0x3157D);
    // Wind from 45-135 degrees left or right of the first course: a crosswind from the start.
    const double side = detail::unit(h, 0) < 0.5 ? -1 : 1;
    wind_from_rad_ = first_course_rad + side * (45 + 90 * detail::unit(h, 1)) * kDeg;
    veer_phase_ = 2 * kPi * detail::unit(h, 2);
    gust_phase_ = 2 * kPi * detail::unit(h, 3);
    alt_phase1_ = 2 * kPi * detail::unit(h, 4);
    alt_phase2_ = 2 * kPi * detail::unit(h, 5);
    alt_period1_s_ = 140 + 60 * detail::unit(h, 6);
    alt_period2_s_ = 70 + 30 * detail::unit(h, 7);
}

double FieldConditions::heading_offset_rad(double t, double course) const {
    double crab = 0;
    if (realism_.crab_max_deg > 0) {
        // Slow veer (+-40 deg over ~7 min) and gusts (0.8-1.0 of the strongest wind, ~40 s period).
        const double wind_from = wind_from_rad_ + 40 * kDeg * std::sin(2 * kPi * t / 420 + veer_phase_);
        const double gust = 0.9 + 0.1 * std::sin(2 * kPi * t / 37 + gust_phase_);
        const double ratio = std::sin(realism_.crab_max_deg * kDeg) * gust;  // wind speed / airspeed
        // Heading into the wind: the camera turns towards where the wind comes from.
        crab = std::asin(std::clamp(ratio * std::sin(wind_from - course), -1.0, 1.0));
    }
    return crab + realism_.mount_yaw_deg * kDeg;
}

double FieldConditions::altitude_m(double t) const {
    if (!(realism_.altitude_change > 0)) return nominal_altitude_m_;
    const double p = 0.65 * std::sin(2 * kPi * t / alt_period1_s_ + alt_phase1_) + 0.35 * std::sin(2 * kPi * t / alt_period2_s_ + alt_phase2_);
    return nominal_altitude_m_ * (1 + realism_.altitude_change * p);
}

}  // namespace trn::sim
