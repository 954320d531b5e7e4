// MAVLink v2 out through the C API: thin over trn::io::mavlink::Stream (trn/io/mavlink_stream.hpp).
#include <cmath>
#include <string>

#include "c_status.hpp"
#include "trn/error.hpp"
#include "trn/io/mavlink_stream.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;
namespace mav = trn::io::mavlink;

struct trn_mavlink_encoder {
    mav::Stream stream;
};

namespace {

mav::NavFix to_cxx(const trn_nav_fix& c) {
    mav::NavFix f;
    f.time_us = c.time_us, f.valid = c.valid != 0, f.reset = c.reset != 0;
    f.lat_deg = c.lat_deg, f.lon_deg = c.lon_deg, f.alt_msl_m = c.alt_msl_m, f.north_m = c.north_m, f.east_m = c.east_m;
    f.cov_nn = c.cov_nn, f.cov_ne = c.cov_ne, f.cov_ee = c.cov_ee, f.spread_m = c.spread_m;
    f.vel_north = c.vel_north, f.vel_east = c.vel_east, f.vel_var = c.vel_var, f.yaw_rad = c.yaw_rad, f.yaw_var = c.yaw_var;
    f.processing_us = c.processing_us;
    return f;
}

}  // namespace

extern "C" {

trn_nav_fix trn_nav_fix_default(void) {
    const mav::NavFix d;  // the C++ defaults
    trn_nav_fix c{};
    c.time_us = d.time_us, c.valid = d.valid, c.reset = d.reset;
    c.lat_deg = d.lat_deg, c.lon_deg = d.lon_deg, c.alt_msl_m = d.alt_msl_m, c.north_m = d.north_m, c.east_m = d.east_m;
    c.cov_nn = d.cov_nn, c.cov_ne = d.cov_ne, c.cov_ee = d.cov_ee, c.spread_m = d.spread_m;
    c.vel_north = d.vel_north, c.vel_east = d.vel_east, c.vel_var = d.vel_var, c.yaw_rad = d.yaw_rad, c.yaw_var = d.yaw_var;
    c.processing_us = d.processing_us;
    return c;
}

trn_mavlink_options trn_mavlink_options_default(void) {
    const mav::StreamConfig d;
    trn_mavlink_options o{};
    o.system_id = d.identity.system_id, o.component_id = d.identity.component_id;
    o.messages = d.messages, o.sensor_id = d.sensor_id, o.satellites = d.satellites;
    return o;
}

trn_status trn_mavlink_encoder_create(const trn_mavlink_options* options, trn_mavlink_encoder** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        const trn_mavlink_options o = options ? *options : trn_mavlink_options_default();
        mav::StreamConfig c;
        c.identity = {o.system_id, o.component_id};
        c.messages = o.messages, c.sensor_id = o.sensor_id, c.satellites = o.satellites;
        if (c.messages == 0 || (c.messages & ~static_cast<unsigned>(mav::kSendAll)) != 0)
            throw InvalidArgument("options->messages " + std::to_string(o.messages) +
                                  " is not a set of TRN_MAVLINK_GPS_INPUT, TRN_MAVLINK_GLOBAL_POSITION, TRN_MAVLINK_ODOMETRY");
        *out = new trn_mavlink_encoder{mav::Stream(c)};
    });
}

trn_status trn_mavlink_encode(trn_mavlink_encoder* encoder, const trn_nav_fix* fix, uint8_t* buffer, size_t capacity, size_t* size) {
    return guarded(__func__, [&] {
        require_pointer(encoder, "encoder");
        require_pointer(fix, "fix");
        require_pointer(buffer, "buffer");
        require_pointer(size, "size");
        *size = 0;
        const mav::Stream before = encoder->stream;  // restored when the bytes do not fit
        std::vector<std::uint8_t> bytes;
        try {
            bytes = encoder->stream.step(to_cxx(*fix));
        } catch (const trn::Error& e) {  // the fix's own fields: the caller's argument
            throw InvalidArgument(std::string("fix: ") + e.what());
        }
        if (bytes.size() > capacity) {
            encoder->stream = before;
            throw InvalidArgument("capacity " + std::to_string(capacity) + " is too small for " + std::to_string(bytes.size()) +
                                  " bytes (TRN_MAVLINK_MAX_BYTES always suffices)");
        }
        std::copy(bytes.begin(), bytes.end(), buffer);
        *size = bytes.size();
    });
}

void trn_mavlink_encoder_destroy(trn_mavlink_encoder* encoder) { delete encoder; }

}  // extern "C"
