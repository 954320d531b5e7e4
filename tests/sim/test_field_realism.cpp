// Field realism of the "-wind" presets: the camera heading is not the course (wind crab, mount
// yaw), the altitude climbs and descends, the barometer is noisy and the odometry's direction
// drifts. The AIR presets keep none of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim_test_maps.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/flight.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {


struct FlightStats {
    double min_offset_deg = 1e9, max_offset_deg = -1e9;  // camera heading - course
    double min_alt = 1e9, max_alt = -1e9;
    double baro_sd = 0, baro_max_abs = 0;
    double max_climb_mps = 0;
};

FlightStats fly(const Scenario& scenario, std::uint64_t seed = 3) {
    FlightConfig cfg;
    cfg.scenario = scenario;
    cfg.render_images = false;
    cfg.seed = seed;
    FlightSimulator sim(testing::forest_map(), cfg);
    FlightStats s;
    FlightFrame f;
    double sum2 = 0, prev_alt = NAN;
    int n = 0;
    while (sim.next(f)) {
        const double offset = wrap_angle(f.truth.yaw_rad - f.truth.course_rad) / kDeg;
        s.min_offset_deg = std::min(s.min_offset_deg, offset), s.max_offset_deg = std::max(s.max_offset_deg, offset);
        s.min_alt = std::min(s.min_alt, f.truth.altitude_m), s.max_alt = std::max(s.max_alt, f.truth.altitude_m);
        const double e = f.baro_altitude_m - f.truth.altitude_m;
        sum2 += e * e, s.baro_max_abs = std::max(s.baro_max_abs, std::abs(e));
        EXPECT_NEAR(f.position_m.z, f.truth.altitude_m, 1e-9);
        if (std::isfinite(prev_alt)) s.max_climb_mps = std::max(s.max_climb_mps, std::abs(f.truth.altitude_m - prev_alt) * scenario.fps);
        prev_alt = f.truth.altitude_m;
        ++n;
    }
    s.baro_sd = std::sqrt(sum2 / n);
    return s;
}

TEST(FieldRealism, WindPresetCrabsClimbsAndHasANoisyBarometer) {
    const Scenario& s = find_scenario("FR-200-wind");
    const FlightStats st = fly(s);
    // Crab up to 30 degrees, both ways round the rectangle, varying.
    EXPECT_LE(std::max(-st.min_offset_deg, st.max_offset_deg), 30.0 + 1e-9);
    EXPECT_GT(std::max(-st.min_offset_deg, st.max_offset_deg), 20.0);
    EXPECT_GT(st.max_offset_deg - st.min_offset_deg, 20.0);
    // Climbs and descents within +-30 % of 200 m, at a plausible rate.
    EXPECT_GE(st.min_alt, 140 - 1e-9);
    EXPECT_LE(st.max_alt, 260 + 1e-9);
    EXPECT_GT(st.max_alt, 200 * 1.15);
    EXPECT_LT(st.min_alt, 200 * 0.85);
    EXPECT_LT(st.max_climb_mps, 8.0);
    // The barometer is off by metres, not by nothing and not by tens.
    EXPECT_GT(st.baro_sd, 1.0);
    EXPECT_LT(st.baro_max_abs, 30.0);
}

TEST(FieldRealism, AirPresetsPointAlongTheTrackAtOneKnownAltitude) {
    const FlightStats st = fly(find_scenario("FR-200"));
    EXPECT_EQ(st.min_offset_deg, 0);
    EXPECT_EQ(st.max_offset_deg, 0);
    EXPECT_EQ(st.min_alt, 200);
    EXPECT_EQ(st.max_alt, 200);
    EXPECT_EQ(st.baro_max_abs, 0);
}

TEST(FieldRealism, MountYawIsAConstantOffset) {
    Scenario s = find_scenario("FC-200");
    s.realism.mount_yaw_deg = -25;
    const FlightStats st = fly(s);
    EXPECT_NEAR(st.min_offset_deg, -25, 1e-9);
    EXPECT_NEAR(st.max_offset_deg, -25, 1e-9);
}

TEST(FieldRealism, BadRealismIsRefusedByName) {
    Scenario s = find_scenario("FR-200");
    s.realism.altitude_change = 0.9;
    FlightConfig cfg;
    cfg.scenario = s;
    try {
        FlightSimulator sim(testing::forest_map(), cfg);
        FAIL() << "no throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("altitude_change"), std::string::npos) << e.what();
    }
}

TEST(FieldRealism, OdometryDirectionAndScaleWalkOnStraightLegs) {
    // Straight flight (no turns): without the walk the heading error stays at its bias; with it,
    // its spread over seeds grows like walk * sqrt(t).
    auto spread = [](double walk_deg, double scale_walk) {
        double sum2 = 0, scale2 = 0;
        const int seeds = 200;
        for (int seed = 1; seed <= seeds; ++seed) {
            OdometryConfig c;
            c.heading_bias_deg = 0, c.scale_error = 0;
            c.heading_walk_deg_per_sqrt_s = walk_deg, c.scale_walk_per_sqrt_s = scale_walk;
            c.seed = seed;
            OdometrySimulator odo(c);
            for (int i = 0; i < 100 * 50; ++i) odo.step({0.24, 0, 0}, 0.02, 0);  // 100 s east
            sum2 += odo.heading_error_rad() * odo.heading_error_rad(), scale2 += odo.scale_error() * odo.scale_error();
        }
        return std::array<double, 2>{std::sqrt(sum2 / seeds) / kDeg, std::sqrt(scale2 / seeds)};
    };
    EXPECT_EQ(spread(0, 0)[0], 0);
    const auto s = spread(0.15, 0.002);
    EXPECT_NEAR(s[0], 1.5, 0.3);    // 0.15 deg/sqrt(s) * 10 sqrt(s)
    EXPECT_NEAR(s[1], 0.02, 0.004);
}

TEST(FieldRealism, AirRecordCarriesTheBarometricAltitude) {
    FlightConfig cfg;
    cfg.scenario = find_scenario("UR-200-wind");
    cfg.render_images = false;
    cfg.frames = 400;
    FlightSimulator sim(testing::urban_map(), cfg);
    FlightFrame f;
    int differs = 0;
    while (sim.next(f)) {
        const AirRecord r = make_air_record(f, "x.png");
        EXPECT_EQ(r.relative_altitude_m, f.baro_altitude_m);  // what a real autopilot logs
        EXPECT_EQ(r.pose_m.z, f.truth.altitude_m);             // the truth stays in PoseZ
        differs += r.relative_altitude_m != r.pose_m.z;
        // The localizer's scale comes from the barometer, the truth pose's from the true altitude.
        EXPECT_NEAR(measured_template_scale(f, cfg.camera, 1.0) / f.template_scale, f.baro_altitude_m / f.truth.altitude_m, 1e-9);
    }
    EXPECT_GT(differs, 390);
}

}  // namespace
}  // namespace trn::sim
