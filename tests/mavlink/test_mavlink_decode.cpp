// Every message trnkit emits, decoded by an independent decoder: node-mavlink (framing, CRC with the
// CRC_EXTRA generated from the MAVLink XML, v2 zero-fill), run as a process on the bytes we wrote.
// Every field it reads must be the value we encoded. SKIPPED (visibly) without node or node-mavlink
// (scripts/install-deps.sh installs both).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli/cli_process.hpp"
#include "trn/io/mavlink.hpp"
#include "trn/io/mavlink_stream.hpp"

namespace mav = trn::io::mavlink;
using nlohmann::json;

namespace {

const std::string kDecoder = std::string(TRN_MAVLINK_DECODER_DIR) + "/decode_mavlink.js";

// Why the decoder cannot run here, or "".
std::string decoder_missing() {
    if (std::string(TRN_NODE).empty() || !std::filesystem::exists(TRN_NODE)) return "node (nodejs) not found when configuring";
    if (!std::filesystem::exists(std::string(TRN_MAVLINK_DECODER_DIR) + "/node_modules/node-mavlink/package.json"))
        return "node-mavlink not installed in " TRN_MAVLINK_DECODER_DIR " (run scripts/install-deps.sh)";
    return "";
}

// The decoder's JSON lines for these bytes.
std::vector<json> decode(const std::vector<std::uint8_t>& bytes) {
    const auto file = std::filesystem::temp_directory_path() / ("trn_mavlink_" + std::to_string(::getpid()) + ".bin");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    const trn::test::CliResult r = trn::test::run_shell(std::string("'") + TRN_NODE + "' '" + kDecoder + "' '" + file.string() + "'");
    const std::string& out = r.output;
    std::filesystem::remove(file);
    EXPECT_EQ(r.code, 0) << out;
    std::vector<json> lines;
    std::size_t at = 0;
    for (std::size_t nl; (nl = out.find('\n', at)) != std::string::npos; at = nl + 1) lines.push_back(json::parse(out.substr(at, nl - at)));
    return lines;
}

// A float field as the decoder printed it ("NaN" for NaN) equals what we encoded, bit for bit.
void expect_float(const json& got, float want, const std::string& what) {
    if (std::isnan(want)) {
        EXPECT_EQ(got, "NaN") << what;
    } else {
        ASSERT_TRUE(got.is_number()) << what << ": " << got;
        EXPECT_EQ(got.get<float>(), want) << what;
    }
}
template <std::size_t N>
void expect_floats(const json& got, const std::array<float, N>& want, const std::string& what) {
    ASSERT_EQ(got.size(), N) << what;
    for (std::size_t i = 0; i < N; ++i) expect_float(got[i], want[i], what + "[" + std::to_string(i) + "]");
}

void expect_fields(const json& f, const mav::Heartbeat& m) {
    EXPECT_EQ(f.size(), 6u);
    EXPECT_EQ(f["type"], m.type);
    EXPECT_EQ(f["autopilot"], m.autopilot);
    EXPECT_EQ(f["base_mode"], m.base_mode);
    EXPECT_EQ(f["custom_mode"], m.custom_mode);
    EXPECT_EQ(f["system_status"], m.system_status);
    EXPECT_EQ(f["mavlink_version"], m.mavlink_version);
}

void expect_fields(const json& f, const mav::GpsInput& m) {
    EXPECT_EQ(f.size(), 19u);
    EXPECT_EQ(f["time_usec"], std::to_string(m.time_usec));
    EXPECT_EQ(f["gps_id"], m.gps_id);
    EXPECT_EQ(f["ignore_flags"], m.ignore_flags);
    EXPECT_EQ(f["time_week_ms"], m.time_week_ms);
    EXPECT_EQ(f["time_week"], m.time_week);
    EXPECT_EQ(f["fix_type"], m.fix_type);
    EXPECT_EQ(f["lat"], m.lat);
    EXPECT_EQ(f["lon"], m.lon);
    for (const auto& [name, v] : {std::pair{"alt", m.alt}, {"hdop", m.hdop}, {"vdop", m.vdop}, {"vn", m.vn}, {"ve", m.ve}, {"vd", m.vd},
                                  {"speed_accuracy", m.speed_accuracy}, {"horiz_accuracy", m.horiz_accuracy},
                                  {"vert_accuracy", m.vert_accuracy}})
        expect_float(f[name], v, name);
    EXPECT_EQ(f["satellites_visible"], m.satellites_visible);
    EXPECT_EQ(f["yaw"], m.yaw);
}

void expect_fields(const json& f, const mav::GlobalPositionSensor& m) {
    EXPECT_EQ(f.size(), 13u);
    EXPECT_EQ(f["target_system"], m.target_system);
    EXPECT_EQ(f["target_component"], m.target_component);
    EXPECT_EQ(f["id"], m.id);
    EXPECT_EQ(f["time_usec"], std::to_string(m.time_usec));
    EXPECT_EQ(f["processing_time"], m.processing_time);
    EXPECT_EQ(f["source"], m.source);
    EXPECT_EQ(f["flags"], m.flags);
    EXPECT_EQ(f["lat"], m.lat);
    EXPECT_EQ(f["lon"], m.lon);
    for (const auto& [name, v] : {std::pair{"alt_ellipsoid", m.alt_ellipsoid}, {"alt", m.alt}, {"eph", m.eph}, {"epv", m.epv}})
        expect_float(f[name], v, name);
}

void expect_fields(const json& f, const mav::Odometry& m) {
    EXPECT_EQ(f.size(), 18u);
    EXPECT_EQ(f["time_usec"], std::to_string(m.time_usec));
    EXPECT_EQ(f["frame_id"], m.frame_id);
    EXPECT_EQ(f["child_frame_id"], m.child_frame_id);
    for (const auto& [name, v] : {std::pair{"x", m.x}, {"y", m.y}, {"z", m.z}, {"vx", m.vx}, {"vy", m.vy}, {"vz", m.vz},
                                  {"rollspeed", m.rollspeed}, {"pitchspeed", m.pitchspeed}, {"yawspeed", m.yawspeed}})
        expect_float(f[name], v, name);
    expect_floats(f["q"], m.q, "q");
    expect_floats(f["pose_covariance"], m.pose_covariance, "pose_covariance");
    expect_floats(f["velocity_covariance"], m.velocity_covariance, "velocity_covariance");
    EXPECT_EQ(f["reset_counter"], m.reset_counter);
    EXPECT_EQ(f["estimator_type"], m.estimator_type);
    EXPECT_EQ(f["quality"], m.quality);
}

// The estimates the cases cover: a full fix, a bare one, one from a spread, lost, reset, odd values.
std::vector<mav::NavFix> cases() {
    std::vector<mav::NavFix> v;
    mav::NavFix f;
    f.time_us = 1'700'000'000'123'456ULL, f.valid = true, f.lat_deg = 41.0349018, f.lon_deg = -83.3057413, f.alt_msl_m = 251.25;
    f.north_m = 120.5, f.east_m = -33.75, f.cov_nn = 16, f.cov_ne = -3, f.cov_ee = 9, f.vel_north = 4.5, f.vel_east = -1.25;
    f.vel_var = 0.36, f.yaw_rad = 2.5, f.yaw_var = 0.04, f.processing_us = 187'000;
    v.push_back(f);
    mav::NavFix bare;  // since boot, position only
    bare.time_us = 2'500'000, bare.valid = true, bare.lat_deg = -33.8688, bare.lon_deg = 151.2093;
    v.push_back(bare);
    mav::NavFix spread = bare;
    spread.time_us += 7'000'000, spread.spread_m = 34.5, spread.north_m = -5, spread.east_m = 0, spread.reset = true;
    v.push_back(spread);
    mav::NavFix lost = f;
    lost.time_us += 100'000, lost.valid = false;
    v.push_back(lost);
    mav::NavFix edge = f;  // the ends of the ranges, north as yaw
    edge.time_us = std::numeric_limits<std::uint64_t>::max() / 2, edge.lat_deg = -90, edge.lon_deg = 180, edge.yaw_rad = 0;
    v.push_back(edge);
    return v;
}

}  // namespace

TEST(MavlinkDecode, NodeMavlinkReadsEveryFieldWeEncode) {
    if (const std::string why = decoder_missing(); !why.empty()) GTEST_SKIP() << "NOT AVAILABLE: " << why;
    mav::StreamConfig config;
    config.identity = {17, 191}, config.sensor_id = 2;
    mav::Stream stream(config);
    std::vector<std::uint8_t> bytes;
    std::vector<json> expected;  // (msgid, the struct encoded) in order, to compare against
    std::vector<std::function<void(const json&)>> checks;
    std::uint8_t resets = 0;
    std::uint64_t last_heartbeat = 0;
    bool first = true;
    for (const mav::NavFix& f : cases()) {
        const std::vector<std::uint8_t> frames = stream.step(f);
        bytes.insert(bytes.end(), frames.begin(), frames.end());
        if (first || f.time_us < last_heartbeat || f.time_us - last_heartbeat >= 1'000'000) {
            mav::Heartbeat h;
            if (!f.valid) h.system_status = 5;
            checks.push_back([h](const json& fields) { expect_fields(fields, h); });
            expected.push_back(0);
            first = false, last_heartbeat = f.time_us;
        }
        if (f.reset) ++resets;
        const mav::GpsInput g = mav::to_gps_input(f, config);
        const mav::GlobalPositionSensor p = mav::to_global_position(f, config);
        const mav::Odometry o = mav::to_odometry(f, resets);
        checks.push_back([g](const json& fields) { expect_fields(fields, g); });
        checks.push_back([p](const json& fields) { expect_fields(fields, p); });
        checks.push_back([o](const json& fields) { expect_fields(fields, o); });
        expected.insert(expected.end(), {232, 296, 331});
    }
    const std::vector<json> lines = decode(bytes);
    ASSERT_EQ(lines.size(), expected.size() + 1) << "one line per packet, then the counts";
    const json& end = lines.back();
    EXPECT_EQ(end["packets"], expected.size());
    EXPECT_EQ(end["crc_errors"], 0) << "node-mavlink's checksum (with its CRC_EXTRA) disagrees with ours";
    EXPECT_EQ(end["unknown"], 0);
    std::size_t offset = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        SCOPED_TRACE("packet " + std::to_string(i) + " " + lines[i].dump().substr(0, 200));
        const json& l = lines[i];
        EXPECT_EQ(l["msgid"], expected[i]);
        EXPECT_EQ(l["magic"], 0xFD);
        EXPECT_EQ(l["seq"], i % 256);
        EXPECT_EQ(l["sysid"], 17);
        EXPECT_EQ(l["compid"], 191);
        EXPECT_EQ(l["incompat"], 0);
        EXPECT_EQ(l["len"], bytes[offset + 1]) << "the truncated length we sent";
        offset += 10 + bytes[offset + 1] + 2;
        checks[i](l["fields"]);
    }
    EXPECT_EQ(offset, bytes.size());
}
