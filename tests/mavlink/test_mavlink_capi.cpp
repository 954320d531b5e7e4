// The C encoder (trn/trnkit.h) is the C++ Stream: the same bytes for the same estimates, and its
// errors name the argument and leave the encoder as it was.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trn/io/mavlink_stream.hpp"
#include "trn/trnkit.h"

extern "C" size_t capi_mavlink_c_encode(uint8_t* out, size_t capacity);

namespace mav = trn::io::mavlink;

TEST(MavlinkCapi, SameBytesAsTheCxxStream) {
    std::vector<std::uint8_t> c(2 * TRN_MAVLINK_MAX_BYTES);
    c.resize(capi_mavlink_c_encode(c.data(), c.size()));
    mav::StreamConfig config;
    config.identity.system_id = 3;
    mav::Stream s(config);
    mav::NavFix f;
    f.time_us = 1700000000000000u, f.valid = true, f.lat_deg = 41.0349018, f.lon_deg = -83.3057413, f.spread_m = 6.5, f.north_m = 10,
    f.east_m = -4;
    std::vector<std::uint8_t> cxx = s.step(f);
    f.valid = false, f.time_us += 200000;
    const std::vector<std::uint8_t> lost = s.step(f);
    cxx.insert(cxx.end(), lost.begin(), lost.end());
    EXPECT_EQ(c, cxx);
    EXPECT_LE(cxx.size() - lost.size(), static_cast<std::size_t>(TRN_MAVLINK_MAX_BYTES));
}

TEST(MavlinkCapi, ErrorsNameTheArgumentAndLeaveTheEncoderAlone) {
    trn_mavlink_encoder* e = nullptr;
    trn_mavlink_options o = trn_mavlink_options_default();
    EXPECT_EQ(o.system_id, 1);
    EXPECT_EQ(o.component_id, 197);
    EXPECT_EQ(o.messages, TRN_MAVLINK_GPS_INPUT | TRN_MAVLINK_GLOBAL_POSITION | TRN_MAVLINK_ODOMETRY);
    o.messages = 8;
    EXPECT_EQ(trn_mavlink_encoder_create(&o, &e), TRN_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(trn_last_error()).find("options->messages 8"), std::string::npos) << trn_last_error();
    ASSERT_EQ(trn_mavlink_encoder_create(nullptr, &e), TRN_OK);
    trn_nav_fix fix = trn_nav_fix_default();
    EXPECT_TRUE(std::isnan(fix.lat_deg) && std::isnan(fix.cov_nn) && fix.valid == 0);
    std::uint8_t buffer[TRN_MAVLINK_MAX_BYTES];
    std::size_t size = 99;
    fix.valid = 1, fix.lat_deg = 95, fix.lon_deg = 0;
    EXPECT_EQ(trn_mavlink_encode(e, &fix, buffer, sizeof buffer, &size), TRN_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(trn_last_error()).find("lat_deg"), std::string::npos) << trn_last_error();
    EXPECT_EQ(size, 0u);
    fix.lat_deg = 45;
    EXPECT_EQ(trn_mavlink_encode(e, &fix, buffer, 20, &size), TRN_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(trn_last_error()).find("capacity 20"), std::string::npos) << trn_last_error();
    EXPECT_EQ(trn_mavlink_encode(e, nullptr, buffer, sizeof buffer, &size), TRN_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(trn_last_error()).find("fix is NULL"), std::string::npos) << trn_last_error();
    ASSERT_EQ(trn_mavlink_encode(e, &fix, buffer, sizeof buffer, &size), TRN_OK);
    EXPECT_EQ(buffer[4], 0) << "the failed calls sent nothing: the first frame has sequence 0";
    EXPECT_EQ(buffer[7], 0) << "and is the first HEARTBEAT";
    trn_mavlink_encoder_destroy(e);
    trn_mavlink_encoder_destroy(nullptr);
}
