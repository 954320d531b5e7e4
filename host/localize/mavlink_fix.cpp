#include "trn/localize/mavlink_fix.hpp"

#include <algorithm>
#include <cmath>

namespace trn::localize {

io::mavlink::NavFix NavFixMaker::fix(const LocalizationRow& row, const Estimate& e) {
    io::mavlink::NavFix f;
    f.time_us = static_cast<std::uint64_t>(std::llround(std::max(0.0, row.time_s) * 1e6));  // the flight's clock
    // No fix: the lock monitor says lost, every weight collapsed (the cloud was scattered anew over
    // the re-initialisation radius) or every particle is off the map; no lat/lon is no position either.
    f.valid = !e.lock.lost && !e.reinitialised && e.particles > 0 && e.off_map < e.particles && std::isfinite(row.estimate_lat) &&
              std::isfinite(row.estimate_lon);
    f.reset = e.reinitialised;
    if (std::isnan(origin_x_)) origin_x_ = row.estimate_x, origin_y_ = row.estimate_y;
    if (f.valid) {
        f.lat_deg = row.estimate_lat, f.lon_deg = row.estimate_lon;
        f.north_m = -(row.estimate_y - origin_y_) * mpp_, f.east_m = (row.estimate_x - origin_x_) * mpp_;  // map y points south
        f.spread_m = e.spread_m;
        f.cov_nn = e.cov_nn_m2, f.cov_ne = e.cov_ne_m2, f.cov_ee = e.cov_ee_m2;
        f.vel_north = e.vel_north_mps, f.vel_east = e.vel_east_mps, f.vel_var = e.vel_var_m2ps2;  // NaN without frame times
        if (compassless_) f.yaw_rad = e.yaw, f.yaw_var = e.yaw_sd * e.yaw_sd;
    }
    f.processing_us = static_cast<std::uint32_t>(std::llround(std::max(0.0, e.step_ms) * 1000));
    return f;
}

}  // namespace trn::localize
