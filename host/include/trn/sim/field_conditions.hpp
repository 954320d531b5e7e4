#pragma once
// Wind crab and altitude profile of a flight with Realism (scenario.hpp): pure functions of time,
// seeded, so a flight is reproducible and any frame can be computed on its own.
#include <cstdint>

#include "trn/sim/scenario.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

class FieldConditions {
public:
    // `first_course_rad`: the course at t = 0 (the wind is placed across it, so the crab shows).
    FieldConditions(const Realism& realism, double nominal_altitude_m, double first_course_rad, std::uint64_t seed);

    // Camera heading minus course (radians): wind crab plus the mount yaw.
    double heading_offset_rad(double time_s, double course_rad) const;
    // True height above ground, metres.
    double altitude_m(double time_s) const;

private:
    Realism realism_;
    double nominal_altitude_m_;
    double wind_from_rad_, veer_phase_, gust_phase_, alt_phase1_, alt_phase2_, alt_period1_s_, alt_period2_s_;
};

}  // namespace trn::sim
TRN_API_END
