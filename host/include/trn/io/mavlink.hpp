#pragma once
// MAVLink v2 frames for the four messages trnkit sends (issue 43; docs/AUTOPILOT.md). Written by
// hand: Debian 12 packages no MAVLink library. Ids, fields, their wire order and CRC_EXTRA are those
// of mavlink/mavlink's message_definitions/v1.0 (minimal.xml, common.xml at de1e078a, 2026-07-22),
// cross-checked against node-mavlink's generated mavlink-mappings 1.0.22-20260311 (the test's decoder).
//
// A frame: 0xFD, payload length, incompat flags (0: unsigned), compat flags, sequence, system id,
// component id, 24-bit message id (little-endian), the payload, then CRC-16/MCRF4XX (X.25) over
// everything after 0xFD plus the message's CRC_EXTRA byte. Payloads are in wire order: fields
// sorted by type size, descending, stable; extension fields after, in XML order. A v2 payload drops
// its trailing zero bytes (at least one byte stays); the receiver fills them back with zeros.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io::mavlink {

struct MessageInfo {
    std::uint32_t id;
    std::uint8_t crc_extra;
    std::uint8_t length;  // full payload, extensions included
    const char* name;
};
inline constexpr MessageInfo kHeartbeat{0, 50, 9, "HEARTBEAT"};
inline constexpr MessageInfo kGpsInput{232, 151, 65, "GPS_INPUT"};
// The map-matching message PX4 fuses as an auxiliary global position (EKF2_AGP*). Issue 43 calls it
// GLOBAL_POSITION: that was its name in development.xml until mavlink/mavlink#2422 (2026-02)
// renamed it and changed its fields (and so its CRC_EXTRA); common.xml has it since #2423.
inline constexpr MessageInfo kGlobalPositionSensor{296, 158, 41, "GLOBAL_POSITION_SENSOR"};
inline constexpr MessageInfo kOdometry{331, 91, 233, "ODOMETRY"};

// CRC-16/MCRF4XX (the X.25 polynomial 0x1021 reflected, initial 0xFFFF, no final xor).
std::uint16_t crc_x25(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0xFFFF);

// Who sends: the companion computer's ids (1 = the vehicle's usual system id; 197 =
// MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY, the closest standard component for a position sensor).
struct Identity {
    std::uint8_t system_id = 1;
    std::uint8_t component_id = 197;
};

// Frames messages with one running sequence number (wraps at 256).
class FrameWriter {
public:
    explicit FrameWriter(Identity identity = {}) : identity_(identity) {}
    // `payload`: the message's full payload (m.length bytes) in wire order. Appends the frame to `out`.
    void append(const MessageInfo& m, std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);
    std::uint8_t next_sequence() const { return seq_; }
    const Identity& identity() const { return identity_; }

private:
    Identity identity_;
    std::uint8_t seq_ = 0;
};

// The messages' fields, named as in the XML (units there). Defaults are each message's "unknown".
struct Heartbeat {
    std::uint8_t type = 18;       // MAV_TYPE_ONBOARD_CONTROLLER
    std::uint8_t autopilot = 8;   // MAV_AUTOPILOT_INVALID: not a flight controller
    std::uint8_t base_mode = 0;
    std::uint32_t custom_mode = 0;
    std::uint8_t system_status = 4;  // MAV_STATE_ACTIVE
    std::uint8_t mavlink_version = 3;
};

struct GpsInput {
    std::uint64_t time_usec = 0;
    std::uint8_t gps_id = 0;
    std::uint16_t ignore_flags = 0;  // GPS_INPUT_IGNORE_FLAGS
    std::uint32_t time_week_ms = 0;
    std::uint16_t time_week = 0;
    std::uint8_t fix_type = 0;       // GPS_FIX_TYPE
    std::int32_t lat = 0, lon = 0;   // degE7
    float alt = 0;                   // m, MSL
    float hdop = 0, vdop = 0;
    float vn = 0, ve = 0, vd = 0;    // m/s, NED
    float speed_accuracy = 0, horiz_accuracy = 0, vert_accuracy = 0;
    std::uint8_t satellites_visible = 0;
    std::uint16_t yaw = 0;           // extension: cdeg, 0 = not available, 36000 = north
};
enum GpsInputIgnore : std::uint16_t {
    kIgnoreAlt = 1, kIgnoreHdop = 2, kIgnoreVdop = 4, kIgnoreVelHoriz = 8, kIgnoreVelVert = 16,
    kIgnoreSpeedAccuracy = 32, kIgnoreHorizontalAccuracy = 64, kIgnoreVerticalAccuracy = 128,
};

struct GlobalPositionSensor {
    std::uint8_t target_system = 0, target_component = 0;  // 0: broadcast
    std::uint8_t id = 0;
    std::uint64_t time_usec = 0;
    std::uint32_t processing_time = 0;  // us
    std::uint8_t source = 0;            // GLOBAL_POSITION_SRC
    std::uint8_t flags = 0;             // GLOBAL_POSITION_FLAGS
    std::int32_t lat = 0, lon = 0;      // degE7, INT32_MAX = invalid
    float alt_ellipsoid = 0, alt = 0, eph = 0, epv = 0;  // m, NaN = invalid
};
inline constexpr std::uint8_t kGlobalPositionSrcVision = 2;  // MAVLink's "Vision" source (e.g. map matching)
inline constexpr std::uint8_t kGlobalPositionUnhealthy = 1;

struct Odometry {
    std::uint64_t time_usec = 0;
    std::uint8_t frame_id = 0, child_frame_id = 0;  // MAV_FRAME
    float x = 0, y = 0, z = 0;                      // m
    std::array<float, 4> q{};                        // w, x, y, z
    float vx = 0, vy = 0, vz = 0;
    float rollspeed = 0, pitchspeed = 0, yawspeed = 0;
    std::array<float, 21> pose_covariance{};     // upper triangle of 6x6 (x y z roll pitch yaw), row-major
    std::array<float, 21> velocity_covariance{};
    std::uint8_t reset_counter = 0;              // extensions from here
    std::uint8_t estimator_type = 0;             // MAV_ESTIMATOR_TYPE
    std::int8_t quality = 0;                     // %, -1 failed, 0 unknown
};
inline constexpr std::uint8_t kFrameLocalNed = 1, kFrameBodyFrd = 12, kEstimatorVision = 2;

// Payloads in wire order, full length (FrameWriter truncates).
std::vector<std::uint8_t> payload(const Heartbeat& m);
std::vector<std::uint8_t> payload(const GpsInput& m);
std::vector<std::uint8_t> payload(const GlobalPositionSensor& m);
std::vector<std::uint8_t> payload(const Odometry& m);

}  // namespace trn::io::mavlink
TRN_API_END
