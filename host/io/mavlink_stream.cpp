// An estimate as MAVLink messages (trn/io/mavlink_stream.hpp; the mapping is in docs/AUTOPILOT.md).
#include "trn/io/mavlink_stream.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "trn/detail/covariance2.hpp"
#include "trn/error.hpp"

namespace trn::io::mavlink {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

std::int32_t degE7(double deg) { return static_cast<std::int32_t>(std::llround(deg * 1e7)); }

float as_float(double v) { return std::isfinite(v) ? static_cast<float>(v) : kNaN; }

// GPS week and milliseconds into it, when time_us is UNIX time (after 2000); 0, 0 for time since boot.
void gps_time(std::uint64_t time_us, std::uint16_t& week, std::uint32_t& week_ms) {
    constexpr std::uint64_t kUnixAt2000Us = 946684800ULL * 1000000;
    constexpr std::uint64_t kGpsEpochUnixS = 315964800;  // 1980-01-06
    constexpr std::uint64_t kLeapSeconds = 18;           // GPS - UTC since 2017-01-01
    week = 0, week_ms = 0;
    if (time_us < kUnixAt2000Us) return;
    const std::uint64_t gps_ms = time_us / 1000 - kGpsEpochUnixS * 1000 + kLeapSeconds * 1000;
    week = static_cast<std::uint16_t>(gps_ms / 604800000ULL);
    week_ms = static_cast<std::uint32_t>(gps_ms % 604800000ULL);
}

bool has_velocity(const NavFix& f) { return std::isfinite(f.vel_north) && std::isfinite(f.vel_east); }

void check_finite_or_nan(double v, const char* name) {
    if (std::isinf(v)) throw Error(std::string("mavlink: NavFix ") + name + " is infinite (NaN means unknown)");
}

void check_variance(double v, const char* name) {
    check_finite_or_nan(v, name);
    if (v < 0) throw Error(std::string("mavlink: NavFix ") + name + " " + std::to_string(v) + " is negative (a variance)");
}

}  // namespace

void check_nav_fix(const NavFix& f) {
    for (const auto& [v, name] : {std::pair{f.lat_deg, "lat_deg"}, {f.lon_deg, "lon_deg"}, {f.alt_msl_m, "alt_msl_m"}, {f.north_m, "north_m"},
                                  {f.east_m, "east_m"}, {f.cov_ne, "cov_ne"}, {f.vel_north, "vel_north"}, {f.vel_east, "vel_east"},
                                  {f.yaw_rad, "yaw_rad"}})
        check_finite_or_nan(v, name);
    for (const auto& [v, name] : {std::pair{f.cov_nn, "cov_nn"}, {f.cov_ee, "cov_ee"}, {f.spread_m, "spread_m"}, {f.vel_var, "vel_var"},
                                  {f.yaw_var, "yaw_var"}})
        check_variance(v, name);
    if (f.lat_deg < -90 || f.lat_deg > 90) throw Error("mavlink: NavFix lat_deg " + std::to_string(f.lat_deg) + " is outside [-90, 90]");
    if (f.lon_deg < -180 || f.lon_deg > 180) throw Error("mavlink: NavFix lon_deg " + std::to_string(f.lon_deg) + " is outside [-180, 180]");
    if (f.valid && !(std::isfinite(f.lat_deg) && std::isfinite(f.lon_deg)))
        throw Error("mavlink: NavFix valid needs lat_deg and lon_deg (set valid = false while there is no position)");
    if (f.cov_ne * f.cov_ne > f.cov_nn * f.cov_ee * (1 + 1e-9))
        throw Error("mavlink: NavFix cov_ne " + std::to_string(f.cov_ne) + " exceeds sqrt(cov_nn * cov_ee): not a covariance");
}

double horizontal_sigma_m(const NavFix& f) {
    if (std::isfinite(f.cov_nn) && std::isfinite(f.cov_ee)) {
        return largest_sigma(f.cov_nn, std::isfinite(f.cov_ne) ? f.cov_ne : 0, f.cov_ee);
    }
    return f.spread_m;
}

GpsInput to_gps_input(const NavFix& f, const StreamConfig& config) {
    GpsInput m;
    m.time_usec = f.time_us;
    m.gps_id = config.sensor_id;
    gps_time(f.time_us, m.time_week, m.time_week_ms);
    // Nothing vertical is measured: altitude only when given, never vdop, vd or a vertical accuracy.
    m.ignore_flags = kIgnoreVdop | kIgnoreVelVert | kIgnoreVerticalAccuracy;
    if (!f.valid) {
        m.fix_type = 1;  // GPS_FIX_TYPE_NO_FIX: the sensor is there, it has no position (0 would say "no GPS")
        m.ignore_flags = 0xFF;
        return m;
    }
    // 3D although the altitude may be unknown: ArduPilot's EKF takes only 3D fixes; an ignored
    // altitude leaves its height to the barometer (docs/AUTOPILOT.md).
    m.fix_type = 3;
    m.lat = degE7(f.lat_deg), m.lon = degE7(f.lon_deg);
    if (std::isfinite(f.alt_msl_m)) m.alt = static_cast<float>(f.alt_msl_m);
    else m.ignore_flags |= kIgnoreAlt;
    // No satellite geometry: hdop 1 passes ArduPilot's GPS_HDOP_GOOD; the accuracy is horiz_accuracy.
    m.hdop = 1;
    const double sigma = horizontal_sigma_m(f);
    if (std::isfinite(sigma)) m.horiz_accuracy = static_cast<float>(sigma);
    else m.ignore_flags |= kIgnoreHorizontalAccuracy;
    if (has_velocity(f)) m.vn = static_cast<float>(f.vel_north), m.ve = static_cast<float>(f.vel_east);
    else m.ignore_flags |= kIgnoreVelHoriz;
    if (has_velocity(f) && std::isfinite(f.vel_var)) m.speed_accuracy = static_cast<float>(std::sqrt(f.vel_var));
    else m.ignore_flags |= kIgnoreSpeedAccuracy;
    m.satellites_visible = config.satellites;
    if (std::isfinite(f.yaw_rad)) {
        const double deg = std::fmod(std::fmod(f.yaw_rad * 180 / kPi, 360) + 360, 360);
        const long cdeg = std::lround(deg * 100);
        m.yaw = static_cast<std::uint16_t>(cdeg == 0 || cdeg >= 36000 ? 36000 : cdeg);  // 0 means "not available"
    }
    return m;
}

GlobalPositionSensor to_global_position(const NavFix& f, const StreamConfig& config) {
    GlobalPositionSensor m;
    m.id = config.sensor_id;
    m.time_usec = f.time_us;
    m.processing_time = f.processing_us;
    m.source = kGlobalPositionSrcVision;
    m.alt_ellipsoid = kNaN, m.epv = kNaN;
    if (!f.valid) {
        m.flags = kGlobalPositionUnhealthy;
        m.lat = m.lon = std::numeric_limits<std::int32_t>::max();
        m.alt = m.eph = kNaN;
        return m;
    }
    m.lat = degE7(f.lat_deg), m.lon = degE7(f.lon_deg);
    m.alt = as_float(f.alt_msl_m);
    m.eph = as_float(horizontal_sigma_m(f));
    return m;
}

Odometry to_odometry(const NavFix& f, std::uint8_t reset_counter) {
    Odometry m;
    m.time_usec = f.time_us;
    m.frame_id = kFrameLocalNed, m.child_frame_id = kFrameLocalNed;  // position and velocity both north-east-down
    m.estimator_type = kEstimatorVision;
    m.reset_counter = reset_counter;
    m.z = kNaN;
    m.rollspeed = m.pitchspeed = m.yawspeed = kNaN;
    m.pose_covariance.fill(kNaN), m.velocity_covariance.fill(kNaN);
    m.q = {kNaN, kNaN, kNaN, kNaN};
    m.vx = m.vy = m.vz = kNaN;
    if (!f.valid) {
        m.x = m.y = kNaN;
        m.quality = -1;  // "odometry has failed"
        return m;
    }
    m.x = as_float(f.north_m), m.y = as_float(f.east_m);
    if (std::isfinite(f.cov_nn) && std::isfinite(f.cov_ee)) {
        m.pose_covariance[0] = static_cast<float>(f.cov_nn), m.pose_covariance[6] = static_cast<float>(f.cov_ee);
        m.pose_covariance[1] = std::isfinite(f.cov_ne) ? static_cast<float>(f.cov_ne) : 0.0f;
    } else if (std::isfinite(f.spread_m)) {  // the same bound as eph, on both axes
        m.pose_covariance[0] = m.pose_covariance[6] = static_cast<float>(f.spread_m * f.spread_m);
        m.pose_covariance[1] = 0;
    }
    if (std::isfinite(f.yaw_rad)) {  // heading only: the quaternion is level, roll/pitch variances unknown
        m.q = {static_cast<float>(std::cos(f.yaw_rad / 2)), 0, 0, static_cast<float>(std::sin(f.yaw_rad / 2))};
        m.pose_covariance[20] = as_float(f.yaw_var);
    }
    if (has_velocity(f)) {
        m.vx = static_cast<float>(f.vel_north), m.vy = static_cast<float>(f.vel_east);
        if (std::isfinite(f.vel_var)) {
            m.velocity_covariance[0] = m.velocity_covariance[6] = static_cast<float>(f.vel_var);
            m.velocity_covariance[1] = 0;
        }
    }
    return m;
}

Stream::Stream(const StreamConfig& config) : config_(config), writer_(config.identity) {
    if (config.messages == 0 || (config.messages & ~static_cast<unsigned>(kSendAll)) != 0)
        throw Error("mavlink: messages " + std::to_string(config.messages) + " is not a set of gps_input (1), global_position (2), odometry (4)");
}

std::vector<std::uint8_t> Stream::step(const NavFix& fix) {
    check_nav_fix(fix);
    std::vector<std::uint8_t> out;
    // 1 Hz of the estimates' own clock; a clock that went back (a new flight) restarts it.
    if (!heartbeat_sent_ || fix.time_us < last_heartbeat_us_ || fix.time_us - last_heartbeat_us_ >= 1000000) {
        Heartbeat h;
        if (!fix.valid) h.system_status = 5;  // MAV_STATE_CRITICAL: lost, no position to give
        writer_.append(kHeartbeat, payload(h), out);
        heartbeat_sent_ = true, last_heartbeat_us_ = fix.time_us;
    }
    if (fix.reset) ++resets_;
    if (config_.messages & kSendGpsInput) writer_.append(kGpsInput, payload(to_gps_input(fix, config_)), out);
    if (config_.messages & kSendGlobalPosition) writer_.append(kGlobalPositionSensor, payload(to_global_position(fix, config_)), out);
    if (config_.messages & kSendOdometry) writer_.append(kOdometry, payload(to_odometry(fix, resets_)), out);
    return out;
}

}  // namespace trn::io::mavlink
