#pragma once
// From a position estimate to the MAVLink messages an autopilot takes (docs/AUTOPILOT.md has the
// mapping field by field). The input is a plain struct, so the C and Python encoders and any filter
// can fill it; the CLI fills it from the Localizer's estimates.
#include <cmath>
#include <cstdint>
#include <vector>

#include "trn/io/mavlink.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io::mavlink {

// One estimate. NaN: not known (its message fields are sent as "unknown" / ignored).
struct NavFix {
    std::uint64_t time_us = 0;         // the frame's time (UNIX epoch or since boot, as MAVLink allows)
    bool valid = false;                // false: lost / no position: "no fix" is sent
    bool reset = false;                // the estimate jumped (re-initialised): ODOMETRY's reset_counter steps
    double lat_deg = NAN, lon_deg = NAN;
    double alt_msl_m = NAN;            // altitude above mean sea level
    double north_m = NAN, east_m = NAN;  // position in a fixed local frame (ODOMETRY), metres from its origin
    // Horizontal position covariance, m^2 (north, east). Without it: spread_m.
    double cov_nn = NAN, cov_ne = NAN, cov_ee = NAN;
    double spread_m = NAN;             // rms distance of the estimate's samples from it
    double vel_north = NAN, vel_east = NAN;  // m/s
    double vel_var = NAN;              // m^2/s^2, per axis
    double yaw_rad = NAN;              // heading, clockwise from true north
    double yaw_var = NAN;              // rad^2
    std::uint32_t processing_us = 0;   // frame to message (GLOBAL_POSITION_SENSOR)
};

enum MessageSet : unsigned {
    kSendGpsInput = 1,
    kSendGlobalPosition = 2,
    kSendOdometry = 4,
    kSendAll = 7,
};

struct StreamConfig {
    Identity identity;
    unsigned messages = kSendAll;     // HEARTBEAT is always sent, at 1 Hz of time_us
    std::uint8_t sensor_id = 0;       // GPS_INPUT gps_id and GLOBAL_POSITION_SENSOR id
    // GPS_INPUT with a fix claims this many satellites: there are none, but ArduPilot's EKF refuses
    // a GPS with fewer than 6 (EK3_GPS_CHECK). 0 while lost.
    std::uint8_t satellites = 10;
};

// The horizontal 1-sigma error an autopilot takes as eph / horiz_accuracy: the square root of the
// covariance's largest eigenvalue (its worst axis); without a covariance, spread_m, which bounds it
// (rms distance^2 = trace >= the largest eigenvalue). NaN when neither is known.
double horizontal_sigma_m(const NavFix& fix);

// The messages for one estimate.
GpsInput to_gps_input(const NavFix& fix, const StreamConfig& config);
GlobalPositionSensor to_global_position(const NavFix& fix, const StreamConfig& config);
Odometry to_odometry(const NavFix& fix, std::uint8_t reset_counter);

// Frames one message set per estimate, with a HEARTBEAT first whenever a second of time_us has
// passed since the last (and before the first estimate).
class Stream {
public:
    explicit Stream(const StreamConfig& config = {});
    // The frames of this estimate, concatenated (a UDP datagram or a serial write).
    std::vector<std::uint8_t> step(const NavFix& fix);
    const StreamConfig& config() const { return config_; }

private:
    StreamConfig config_;
    FrameWriter writer_;
    bool heartbeat_sent_ = false;
    std::uint64_t last_heartbeat_us_ = 0;
    std::uint8_t resets_ = 0;
};

// Checks a NavFix a caller filled (C, Python): trn::Error naming the field (lat_deg out of range ...).
void check_nav_fix(const NavFix& fix);

}  // namespace trn::io::mavlink
TRN_API_END
