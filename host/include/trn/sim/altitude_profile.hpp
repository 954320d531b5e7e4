#pragma once
// The planned altitude of a flight with level changes (Scenario::other_altitude_m, the "-long"
// presets): level legs alternately at the scenario's altitude A and the other altitude B, joined
// by climbs / descents of climb_s seconds with a cosine-shaped height (vertical speed 0 at both
// ends; mean |B - A| / climb_s, peak pi/2 times that: 2.5 and 3.9 m/s for 100 m in 40 s).
// A flight of D seconds has n = max(1, floor((D / climb_s - 1) / 2)) changes, so that every level
// leg lasts at least climb_s when D allows it; the n + 1 legs are equally long. Past D the profile
// runs backwards (and then forwards again), so a longer flight never jumps in height.
#include "trn/sim/scenario.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

class AltitudeProfile {
public:
    explicit AltitudeProfile(const Scenario& scenario);
    // Planned height above ground at time t (scenario.altitude_m throughout without level changes).
    double altitude_m(double time_s) const;
    int changes() const { return changes_; }  // 0 without level changes

private:
    double a_m_, b_m_, duration_s_, climb_s_ = 0, leg_s_ = 0;
    int changes_ = 0;
};

}  // namespace trn::sim
TRN_API_END
