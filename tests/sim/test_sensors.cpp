// Odometry drift and magnetometer noise must match their configuration.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "trn/sim/sensors.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {


// Flies straight north-east at 12 m/s for `seconds` at 50 Hz; returns the final estimate.
Vec3 fly_straight(const OdometryConfig& cfg, double seconds) {
    OdometrySimulator odo(cfg);
    const double dt = 0.02, step = 12 * dt;
    const int n = static_cast<int>(seconds / dt);
    for (int i = 0; i < n; ++i) odo.step({step / std::sqrt(2.0), step / std::sqrt(2.0), 0}, dt, 0);
    return odo.estimate();
}

TEST(Odometry, ScaleErrorAndHeadingBiasAreDeterministicWithoutNoise) {
    OdometryConfig cfg;
    cfg.scale_error = 0.05;
    cfg.heading_bias_deg = 3;
    cfg.random_walk_m_per_sqrt_s = 0;
    const Vec3 e = fly_straight(cfg, 100);
    EXPECT_NEAR(std::hypot(e.x, e.y), 1200 * 1.05, 1e-6);
    const double heading = std::atan2(e.x, e.y);  // compass heading of the estimated track
    EXPECT_NEAR(heading, 45 * kDeg + 3 * kDeg, 1e-9);
}

TEST(Odometry, RandomWalkGrowsWithSquareRootOfTime) {
    OdometryConfig cfg;
    cfg.scale_error = 0;
    cfg.heading_bias_deg = 0;
    cfg.random_walk_m_per_sqrt_s = 0.1;
    const double seconds = 100;
    double sum2 = 0;
    const int runs = 300;
    for (int r = 0; r < runs; ++r) {
        cfg.seed = 1000 + r;
        const Vec3 e = fly_straight(cfg, seconds);
        const double ex = e.x - 1200 / std::sqrt(2.0), ey = e.y - 1200 / std::sqrt(2.0);
        sum2 += ex * ex + ey * ey;
    }
    // Per axis variance sigma^2 * t, two axes.
    const double expected_rms = 0.1 * std::sqrt(seconds) * std::sqrt(2.0);
    EXPECT_NEAR(std::sqrt(sum2 / runs), expected_rms, 0.12 * expected_rms);
}

TEST(Odometry, TurnsAddHeadingErrorWithTheConfiguredSpread) {
    OdometryConfig cfg;
    cfg.heading_bias_deg = 0;
    cfg.random_walk_m_per_sqrt_s = 0;
    cfg.turn_heading_noise_deg_per_sqrt_rad = 2;
    const int runs = 400;
    double sum2 = 0;
    for (int r = 0; r < runs; ++r) {
        cfg.seed = 5000 + r;
        OdometrySimulator odo(cfg);
        // Two full circles (4 pi rad) at 0.2 rad/s.
        const double dt = 0.02, rate = 0.2;
        for (int i = 0; i < static_cast<int>(4 * kPi / rate / dt); ++i) odo.step({0.1, 0, 0}, dt, rate);
        sum2 += odo.heading_error_rad() * odo.heading_error_rad();
    }
    const double expected = 2 * kDeg * std::sqrt(4 * kPi);
    EXPECT_NEAR(std::sqrt(sum2 / runs), expected, 0.12 * expected);
    // No turning: no heading error beyond the bias.
    OdometrySimulator straight(cfg);
    for (int i = 0; i < 1000; ++i) straight.step({0.2, 0, 0}, 0.02, 0);
    EXPECT_EQ(straight.heading_error_rad(), 0.0);
}

TEST(Odometry, SeedMakesRunsReproducible) {
    OdometryConfig cfg;
    const Vec3 a = fly_straight(cfg, 10), b = fly_straight(cfg, 10);
    EXPECT_EQ(a.x, b.x);
    cfg.seed = 2;
    EXPECT_NE(fly_straight(cfg, 10).x, a.x);
}

TEST(Magnetometer, NoiseStaysWithinTwoDegreesWithConfiguredSpread) {
    Magnetometer mag(MagnetometerConfig{});
    double sum = 0, sum2 = 0, worst = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double err = wrap_angle(mag.read(3.1) - 3.1) / kDeg;  // near the wrap-around on purpose
        sum += err, sum2 += err * err, worst = std::max(worst, std::abs(err));
    }
    EXPECT_LE(worst, 2.0 + 1e-9);
    EXPECT_NEAR(sum / n, 0, 0.03);
    // A normal with sigma 1 clipped (not truncated) at 2 sigma has sd sqrt(0.9205) = 0.959.
    EXPECT_NEAR(std::sqrt(sum2 / n), 0.959, 0.03);
}

TEST(Angles, WrapAngle) {
    EXPECT_NEAR(wrap_angle(3 * kPi), kPi, 1e-12);
    EXPECT_NEAR(wrap_angle(-0.5 - 2 * kPi), -0.5, 1e-12);
}

}  // namespace
}  // namespace trn::sim
