// MAVLink v2 out (issue 43): framing, the estimate mapping, endpoints and the UDP sender, by our own
// expectations; test_mavlink_decode.cpp has an independent decoder read the same frames.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trn/error.hpp"
#include "trn/io/mavlink.hpp"
#include "trn/io/mavlink_stream.hpp"
#include "trn/io/mavlink_udp.hpp"

namespace mav = trn::io::mavlink;

namespace {

std::string error_of(const auto& call) {
    try {
        call();
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "(no error)";
}

mav::NavFix a_fix() {
    mav::NavFix f;
    f.time_us = 1'700'000'000'000'000ULL;
    f.valid = true;
    f.lat_deg = 41.0349018, f.lon_deg = -83.3057413, f.alt_msl_m = 250.5;
    f.north_m = 12.5, f.east_m = -3.25;
    f.cov_nn = 16, f.cov_ne = 0, f.cov_ee = 9;
    return f;
}

}  // namespace

TEST(MavlinkFrame, CrcIsMcrf4xx) {
    const std::string check = "123456789";  // the catalogue's check value of CRC-16/MCRF4XX
    EXPECT_EQ(mav::crc_x25({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}), 0x6F91);
}

TEST(MavlinkFrame, HeaderTruncationAndChecksum) {
    mav::FrameWriter w({42, 7});
    mav::Heartbeat h;  // custom_mode 0 first, then type 18 ... mavlink_version 3 last: nothing to cut
    std::vector<std::uint8_t> out;
    w.append(mav::kHeartbeat, mav::payload(h), out);
    ASSERT_EQ(out.size(), 10u + 9 + 2);
    EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + 10), (std::vector<std::uint8_t>{0xFD, 9, 0, 0, 0, 42, 7, 0, 0, 0}));
    std::uint16_t crc = mav::crc_x25(std::span(out).subspan(1, 9 + 9));
    crc = mav::crc_x25(std::span(&mav::kHeartbeat.crc_extra, 1), crc);
    EXPECT_EQ(out[19] | (out[20] << 8), crc);

    // Trailing zeros go, down to one byte; the sequence counts every frame.
    out.clear();
    w.append(mav::kGlobalPositionSensor, std::vector<std::uint8_t>(41, 0), out);
    EXPECT_EQ(out[1], 1) << "an all-zero payload keeps its first byte";
    EXPECT_EQ(out[4], 1) << "second frame";
    EXPECT_EQ(out[7] | (out[8] << 8) | (out[9] << 16), 296);
    out.clear();
    mav::GpsInput g;  // yaw (the extension) 0 and the 1-byte fields 0: cut back to the last non-zero byte
    g.time_usec = 1, g.satellites_visible = 0, g.fix_type = 0;
    w.append(mav::kGpsInput, mav::payload(g), out);
    EXPECT_EQ(out[1], 1);
    EXPECT_THROW(w.append(mav::kOdometry, std::vector<std::uint8_t>(10, 1), out), trn::Error);
}

TEST(MavlinkFrame, SequenceWraps) {
    mav::FrameWriter w;
    std::vector<std::uint8_t> out;
    for (int i = 0; i < 256; ++i) w.append(mav::kHeartbeat, mav::payload(mav::Heartbeat{}), out);
    EXPECT_EQ(w.next_sequence(), 0);
}

TEST(MavlinkFrame, PayloadLengthsAndWireOrder) {
    EXPECT_EQ(mav::payload(mav::Heartbeat{}).size(), 9u);
    EXPECT_EQ(mav::payload(mav::GpsInput{}).size(), 65u);
    EXPECT_EQ(mav::payload(mav::GlobalPositionSensor{}).size(), 41u);
    EXPECT_EQ(mav::payload(mav::Odometry{}).size(), 233u);
    mav::GpsInput g;
    g.time_usec = 0x0102030405060708ULL, g.yaw = 0xBEEF, g.satellites_visible = 9, g.ignore_flags = 0x1234;
    const auto p = mav::payload(g);
    EXPECT_EQ(p[0], 0x08);                      // uint64 first, little-endian
    EXPECT_EQ(p[56] | (p[57] << 8), 0x1234);    // after the 4-byte fields: ignore_flags, time_week
    EXPECT_EQ(p[62], 9);                        // the last 1-byte field
    EXPECT_EQ(p[63] | (p[64] << 8), 0xBEEF);    // the extension after everything
}

TEST(MavlinkMapping, GpsInputWithAFix) {
    mav::NavFix f = a_fix();
    f.vel_north = 1.5, f.vel_east = -2, f.vel_var = 0.25, f.yaw_rad = -M_PI / 2;
    const mav::GpsInput m = mav::to_gps_input(f, {});
    EXPECT_EQ(m.fix_type, 3);
    EXPECT_EQ(m.lat, 410349018);
    EXPECT_EQ(m.lon, -833057413);
    EXPECT_FLOAT_EQ(m.alt, 250.5f);
    EXPECT_FLOAT_EQ(m.horiz_accuracy, 4.0f) << "sqrt of the largest eigenvalue";
    EXPECT_FLOAT_EQ(m.vn, 1.5f);
    EXPECT_FLOAT_EQ(m.ve, -2.0f);
    EXPECT_FLOAT_EQ(m.speed_accuracy, 0.5f);
    EXPECT_EQ(m.yaw, 27000);
    EXPECT_EQ(m.ignore_flags, mav::kIgnoreVdop | mav::kIgnoreVelVert | mav::kIgnoreVerticalAccuracy);
    EXPECT_EQ(m.satellites_visible, 10);
    // 2023-11-14 22:13:20 UTC is GPS week 2288, 252818 s into it (18 leap seconds).
    EXPECT_EQ(m.time_week, 2288);
    EXPECT_EQ(m.time_week_ms, 252818000u);
}

TEST(MavlinkMapping, UnknownFieldsAreIgnoredNotInvented) {
    mav::NavFix f = a_fix();
    f.alt_msl_m = NAN, f.cov_nn = f.cov_ne = f.cov_ee = NAN;
    f.time_us = 5'000'000;  // since boot: no GPS week
    mav::GpsInput m = mav::to_gps_input(f, {});
    EXPECT_EQ(m.ignore_flags & (mav::kIgnoreAlt | mav::kIgnoreHorizontalAccuracy | mav::kIgnoreVelHoriz | mav::kIgnoreSpeedAccuracy),
              mav::kIgnoreAlt | mav::kIgnoreHorizontalAccuracy | mav::kIgnoreVelHoriz | mav::kIgnoreSpeedAccuracy);
    EXPECT_EQ(m.time_week, 0);
    EXPECT_EQ(m.yaw, 0) << "0: not available";
    const mav::GlobalPositionSensor g = mav::to_global_position(f, {});
    EXPECT_TRUE(std::isnan(g.eph));
    EXPECT_TRUE(std::isnan(g.alt));
    f.spread_m = 5;  // no covariance: the spread bounds the worst axis
    EXPECT_DOUBLE_EQ(mav::horizontal_sigma_m(f), 5);
    EXPECT_FLOAT_EQ(mav::to_odometry(f, 0).pose_covariance[0], 25.0f);
    f.yaw_rad = 0;
    EXPECT_EQ(mav::to_gps_input(f, {}).yaw, 36000) << "north is 36000, never 0";
}

TEST(MavlinkMapping, LostSendsNoFix) {
    mav::NavFix f = a_fix();
    f.valid = false;
    const mav::GpsInput g = mav::to_gps_input(f, {});
    EXPECT_EQ(g.fix_type, 1);
    EXPECT_EQ(g.lat, 0);
    EXPECT_EQ(g.ignore_flags, 0xFF);
    EXPECT_EQ(g.satellites_visible, 0);
    const mav::GlobalPositionSensor p = mav::to_global_position(f, {});
    EXPECT_EQ(p.lat, std::numeric_limits<std::int32_t>::max());
    EXPECT_EQ(p.lon, std::numeric_limits<std::int32_t>::max());
    EXPECT_EQ(p.flags, mav::kGlobalPositionUnhealthy);
    const mav::Odometry o = mav::to_odometry(f, 3);
    EXPECT_TRUE(std::isnan(o.x) && std::isnan(o.y));
    EXPECT_EQ(o.quality, -1);
    EXPECT_EQ(o.reset_counter, 3);
}

TEST(MavlinkMapping, Odometry) {
    mav::NavFix f = a_fix();
    f.cov_ne = 2, f.yaw_rad = M_PI / 2, f.yaw_var = 0.01;
    const mav::Odometry o = mav::to_odometry(f, 0);
    EXPECT_EQ(o.frame_id, mav::kFrameLocalNed);
    EXPECT_FLOAT_EQ(o.x, 12.5f);
    EXPECT_FLOAT_EQ(o.y, -3.25f);
    EXPECT_TRUE(std::isnan(o.z));
    EXPECT_FLOAT_EQ(o.pose_covariance[0], 16);
    EXPECT_FLOAT_EQ(o.pose_covariance[1], 2);
    EXPECT_FLOAT_EQ(o.pose_covariance[6], 9);
    EXPECT_FLOAT_EQ(o.pose_covariance[20], 0.01f);
    EXPECT_NEAR(o.q[0], std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(o.q[3], std::sqrt(0.5), 1e-6);
    EXPECT_TRUE(std::isnan(o.vx)) << "no velocity given";
    EXPECT_TRUE(std::isnan(o.velocity_covariance[0]));
}

TEST(MavlinkStream, HeartbeatAtOneHertzOfTheEstimatesClock) {
    mav::Stream s(mav::StreamConfig{{}, mav::kSendGlobalPosition});
    mav::NavFix f = a_fix();
    auto heartbeats = [](const std::vector<std::uint8_t>& bytes) {
        int n = 0;
        for (std::size_t i = 0; i + 10 <= bytes.size(); i += 10 + bytes[i + 1] + 2) n += bytes[i + 7] == 0 && bytes[i + 8] == 0;
        return n;
    };
    int total = 0;
    for (int i = 0; i < 50; ++i, f.time_us += 100'000) total += heartbeats(s.step(f));  // 5 s at 10 Hz
    EXPECT_EQ(total, 5);
    f.time_us = 0;  // a new flight's clock
    EXPECT_EQ(heartbeats(s.step(f)), 1);
}

TEST(MavlinkStream, BadInputNamesTheField) {
    mav::Stream s;
    mav::NavFix f = a_fix();
    f.lat_deg = 91;
    EXPECT_NE(error_of([&] { s.step(f); }).find("lat_deg"), std::string::npos);
    f = a_fix(), f.cov_nn = -1;
    EXPECT_NE(error_of([&] { s.step(f); }).find("cov_nn"), std::string::npos);
    f = a_fix(), f.cov_ne = 20;
    EXPECT_NE(error_of([&] { s.step(f); }).find("not a covariance"), std::string::npos);
    f = a_fix(), f.lon_deg = NAN;
    EXPECT_NE(error_of([&] { s.step(f); }).find("valid needs"), std::string::npos);
    f = a_fix(), f.vel_east = INFINITY;
    EXPECT_NE(error_of([&] { s.step(f); }).find("vel_east"), std::string::npos);
    EXPECT_NE(error_of([] { mav::Stream bad(mav::StreamConfig{{}, 8}); }).find("messages"), std::string::npos);
}

TEST(MavlinkEndpoint, TheFormsMavlinkUsersWrite) {
    for (const char* text : {"udp:127.0.0.1:14550", "udpout:127.0.0.1:14550", "udpout://127.0.0.1:14550"}) {
        const mav::Endpoint e = mav::parse_endpoint(text);
        EXPECT_EQ(e.host, "127.0.0.1") << text;
        EXPECT_EQ(e.port, 14550) << text;
    }
    EXPECT_EQ(mav::parse_endpoint("udp:[::1]:5760").host, "::1");
    EXPECT_EQ(mav::parse_endpoint("udp:localhost:1").port, 1);
    const std::pair<const char*, const char*> refused[] = {
        {"udpin:0.0.0.0:14550", "only sends"}, {"udp://:14540", "listens"},      {"tcp:127.0.0.1:5760", "only UDP"},
        {"/dev/ttyACM0", "only UDP"},          {"udp:127.0.0.1", "no port"},     {"udp::14550", "no host"},
        {"udp:127.0.0.1:0", "1..65535"},       {"udp:127.0.0.1:70000", "1..65535"}, {"udp:::1:14550", "brackets"},
        {"14550", "expected udp:HOST:PORT"}};
    for (const auto& [text_binding, why] : refused) {
        const char* text = text_binding;  // a lambda captures structured bindings only from Clang 16
        const std::string message = error_of([&] { mav::parse_endpoint(text, "--mavlink"); });
        EXPECT_EQ(message.rfind(std::string("--mavlink ") + text, 0), 0u) << message;
        EXPECT_NE(message.find(why), std::string::npos) << message;
    }
}

TEST(MavlinkUdp, DatagramsArriveWhole) {
    const int rx = socket(AF_INET, SOCK_DGRAM, 0);
    ASSERT_GE(rx, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET, a.sin_addr.s_addr = htonl(INADDR_LOOPBACK), a.sin_port = 0;
    ASSERT_EQ(bind(rx, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ASSERT_EQ(getsockname(rx, reinterpret_cast<sockaddr*>(&a), &len), 0);
    timeval tv{5, 0};
    setsockopt(rx, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);

    mav::UdpSender tx(mav::parse_endpoint("udp:127.0.0.1:" + std::to_string(ntohs(a.sin_port))));
    mav::Stream s;
    const std::vector<std::uint8_t> frames = s.step(a_fix());
    tx.send(frames);
    std::vector<std::uint8_t> got(2048);
    const ssize_t n = recv(rx, got.data(), got.size(), 0);
    close(rx);
    ASSERT_EQ(n, static_cast<ssize_t>(frames.size()));
    got.resize(static_cast<std::size_t>(n));
    EXPECT_EQ(got, frames);
    EXPECT_EQ(tx.sent(), 1u);
    EXPECT_NE(error_of([] { mav::UdpSender bad({"no-such-host.invalid", 14550}); }).find("is not a numeric IP address"), std::string::npos);
}
