#pragma once
// One Localizer step as the MAVLink estimate that `trnkit localize --mavlink` streams
// (io::mavlink::NavFix; docs/AUTOPILOT.md, "What localize --mavlink fills in"). One home for that
// mapping, so the CLI and the frame-to-message benchmark (bench/latency_benches.cpp) send the same.
#include <cmath>

#include "trn/io/mavlink_stream.hpp"
#include "trn/localize/localization.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

class NavFixMaker {
public:
    // compassless: the yaw is the filter's own estimate, so it is sent (a compass run would echo the compass back).
    NavFixMaker(double metres_per_pixel, bool compassless) : mpp_(metres_per_pixel), compassless_(compassless) {}
    // `row`: the step's row with estimate_lat/lon filled (RunHooks::step gives it so on a
    // georeferenced map); without them the step is sent as no fix. time_us: the row's time_s (the
    // flight's clock); north/east: metres from the first estimate; processing_us: the step's wall time.
    io::mavlink::NavFix fix(const LocalizationRow& row, const Estimate& e);

private:
    double mpp_;
    bool compassless_;
    double origin_x_ = NAN, origin_y_ = NAN;  // ODOMETRY's local frame: metres from the first estimate
};

}  // namespace trn::localize
TRN_API_END
