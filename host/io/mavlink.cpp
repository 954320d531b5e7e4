// MAVLink v2 framing and the four payloads (trn/io/mavlink.hpp).
#include "trn/io/mavlink.hpp"

#include <bit>
#include <cstring>
#include <string>

#include "trn/error.hpp"

namespace trn::io::mavlink {
namespace {

// Little-endian field writer; the wire order is the order of the put() calls.
class Payload {
public:
    explicit Payload(std::size_t length) { bytes_.reserve(length); }
    template <typename T>
    Payload& put(T v) {
        static_assert(std::endian::native == std::endian::little, "MAVLink is little-endian; add byte swaps for this target");
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        bytes_.insert(bytes_.end(), b, b + sizeof(T));
        return *this;
    }
    template <typename T, std::size_t N>
    Payload& put(const std::array<T, N>& a) {
        for (const T& v : a) put(v);
        return *this;
    }
    std::vector<std::uint8_t> done(const MessageInfo& m) {
        if (bytes_.size() != m.length)  // a field list that disagrees with the definition's length
            throw Error(std::string("mavlink: ") + m.name + " payload is " + std::to_string(bytes_.size()) + " bytes, not " +
                        std::to_string(m.length));
        return std::move(bytes_);
    }

private:
    std::vector<std::uint8_t> bytes_;
};

}  // namespace

std::uint16_t crc_x25(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
    for (const std::uint8_t b : bytes) {
        std::uint8_t t = b ^ static_cast<std::uint8_t>(crc & 0xFF);
        t ^= static_cast<std::uint8_t>(t << 4);
        crc = static_cast<std::uint16_t>((crc >> 8) ^ (t << 8) ^ (t << 3) ^ (t >> 4));
    }
    return crc;
}

void FrameWriter::append(const MessageInfo& m, std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out) {
    if (payload.size() != m.length)
        throw Error(std::string("mavlink: ") + m.name + " payload must be " + std::to_string(m.length) + " bytes, got " +
                    std::to_string(payload.size()));
    std::size_t len = payload.size();
    while (len > 1 && payload[len - 1] == 0) --len;  // v2 truncation; the first byte always stays
    const std::size_t start = out.size();
    out.insert(out.end(), {0xFD, static_cast<std::uint8_t>(len), 0, 0, seq_++, identity_.system_id, identity_.component_id,
                           static_cast<std::uint8_t>(m.id & 0xFF), static_cast<std::uint8_t>((m.id >> 8) & 0xFF),
                           static_cast<std::uint8_t>((m.id >> 16) & 0xFF)});
    out.insert(out.end(), payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(len));
    std::uint16_t crc = crc_x25(std::span(out).subspan(start + 1));
    crc = crc_x25(std::span(&m.crc_extra, 1), crc);
    out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    out.push_back(static_cast<std::uint8_t>(crc >> 8));
}

// Each put() sequence below is the definition's fields sorted by size (stable), extensions last.
std::vector<std::uint8_t> payload(const Heartbeat& m) {
    return Payload(kHeartbeat.length).put(m.custom_mode).put(m.type).put(m.autopilot).put(m.base_mode).put(m.system_status)
        .put(m.mavlink_version).done(kHeartbeat);
}

std::vector<std::uint8_t> payload(const GpsInput& m) {
    return Payload(kGpsInput.length).put(m.time_usec).put(m.time_week_ms).put(m.lat).put(m.lon).put(m.alt).put(m.hdop).put(m.vdop)
        .put(m.vn).put(m.ve).put(m.vd).put(m.speed_accuracy).put(m.horiz_accuracy).put(m.vert_accuracy).put(m.ignore_flags)
        .put(m.time_week).put(m.gps_id).put(m.fix_type).put(m.satellites_visible)
        .put(m.yaw)  // extension
        .done(kGpsInput);
}

std::vector<std::uint8_t> payload(const GlobalPositionSensor& m) {
    return Payload(kGlobalPositionSensor.length).put(m.time_usec).put(m.processing_time).put(m.lat).put(m.lon).put(m.alt_ellipsoid)
        .put(m.alt).put(m.eph).put(m.epv).put(m.target_system).put(m.target_component).put(m.id).put(m.source).put(m.flags)
        .done(kGlobalPositionSensor);
}

std::vector<std::uint8_t> payload(const Odometry& m) {
    return Payload(kOdometry.length).put(m.time_usec).put(m.x).put(m.y).put(m.z).put(m.q).put(m.vx).put(m.vy).put(m.vz)
        .put(m.rollspeed).put(m.pitchspeed).put(m.yawspeed).put(m.pose_covariance).put(m.velocity_covariance).put(m.frame_id)
        .put(m.child_frame_id)
        .put(m.reset_counter).put(m.estimator_type).put(m.quality)  // extensions
        .done(kOdometry);
}

}  // namespace trn::io::mavlink
