// Issue 43 item 2: the online Localizer's uncertainty an autopilot can take. The covariance is the
// particles' own (its trace is the spread), turned into metres north/east with the right signs; eph
// is its worst axis; latitude / longitude come with a map origin; velocity needs frame times; and a
// localized flight reports how often the truth lies inside the 1- and 2-sigma ellipses.
#include <gtest/gtest.h>

#include <cmath>

#include "filter_test_world.hpp"
#include "trn/error.hpp"
#include "trn/localize/localization.hpp"

namespace trn::filter::testing {
namespace {

struct LocalizerOnTestWorld {
    std::unique_ptr<Backend> backend = default_registry().create("cpu");
    localize::LocalizerConfig config;
    LocalizerOnTestWorld() {
        config.start_x = 800, config.start_y = 700;
        config.filter.init_radius_m = 30;
    }
    localize::Localizer make() const {
        return localize::Localizer(test_world().map.image.view(), test_world().map.metres_per_pixel, *backend, config);
    }
};

localize::Observation no_frame(double east_m, double north_m, double time_s) {
    localize::Observation o;
    o.odometry_east_m = east_m, o.odometry_north_m = north_m, o.heading_rad = 0.3, o.time_s = time_s;
    return o;
}

TEST(Uncertainty, CovarianceIsTheParticlesAndItsTraceIsTheSpread) {
    LocalizerOnTestWorld run;
    localize::Localizer l = run.make();
    const double mpp = l.metres_per_pixel();
    const localize::Estimate e = l.step(no_frame(3, 4, NAN));
    // Recomputed from the particles the Localizer holds.
    double sw = 0, xx = 0, xy = 0, yy = 0;
    for (const Particle& p : l.particles()) sw += p.weight;
    for (const Particle& p : l.particles()) {
        const double dx = p.x - e.x, dy = p.y - e.y;
        xx += p.weight * dx * dx / sw, xy += p.weight * dx * dy / sw, yy += p.weight * dy * dy / sw;
    }
    EXPECT_NEAR(e.cov_xx_px2, xx, 1e-9 * xx);
    EXPECT_NEAR(e.cov_xy_px2, xy, 1e-9 * (xx + yy));
    EXPECT_NEAR(e.cov_yy_px2, yy, 1e-9 * yy);
    EXPECT_GT(e.cov_xx_px2, 1.0) << "a 30 m start disc is not a point";
    EXPECT_NEAR((e.cov_xx_px2 + e.cov_yy_px2) * mpp * mpp, e.spread_m * e.spread_m, 1e-9 * e.spread_m * e.spread_m);
    // Metres, north/east: y points south, so the cross term changes sign.
    EXPECT_DOUBLE_EQ(e.cov_ee_m2, e.cov_xx_px2 * mpp * mpp);
    EXPECT_DOUBLE_EQ(e.cov_nn_m2, e.cov_yy_px2 * mpp * mpp);
    EXPECT_DOUBLE_EQ(e.cov_ne_m2, -e.cov_xy_px2 * mpp * mpp);
    // eph: the largest eigenvalue's root, between the mean and the whole of the trace.
    const double trace = e.cov_ee_m2 + e.cov_nn_m2;
    EXPECT_GE(e.eph_m * e.eph_m, trace / 2 * (1 - 1e-12));
    EXPECT_LE(e.eph_m * e.eph_m, trace * (1 + 1e-12));
    const double lambda = e.eph_m * e.eph_m;  // det(C - lambda I) = 0
    EXPECT_NEAR((e.cov_ee_m2 - lambda) * (e.cov_nn_m2 - lambda) - e.cov_ne_m2 * e.cov_ne_m2, 0, 1e-6 * trace * trace);
    EXPECT_TRUE(std::isnan(e.latitude_deg)) << "no map origin, no latitude";
}

TEST(Uncertainty, VelocityNeedsTwoFrameTimes) {
    LocalizerOnTestWorld run;
    localize::Localizer l = run.make();
    const double mpp = l.metres_per_pixel();
    const localize::Estimate first = l.step(no_frame(0, 0, 100.0));
    EXPECT_TRUE(std::isnan(first.vel_north_mps)) << "no previous step";
    EXPECT_EQ(first.time_s, 100.0);
    const localize::Estimate second = l.step(no_frame(6, 8, 102.0));
    ASSERT_TRUE(std::isfinite(second.vel_east_mps));
    EXPECT_DOUBLE_EQ(second.vel_east_mps, (second.x - first.x) * mpp / 2);
    EXPECT_DOUBLE_EQ(second.vel_north_mps, -(second.y - first.y) * mpp / 2);
    EXPECT_NEAR(second.vel_east_mps, 3, 1.0) << "6 m east in 2 s";
    EXPECT_NEAR(second.vel_north_mps, 4, 1.0) << "8 m north in 2 s";
    const double per_axis = (first.cov_ee_m2 + first.cov_nn_m2 + second.cov_ee_m2 + second.cov_nn_m2) / 4;
    EXPECT_DOUBLE_EQ(second.vel_var_m2ps2, 2 * per_axis / 4);
    const localize::Estimate untimed = l.step(no_frame(6, 8, NAN));
    EXPECT_TRUE(std::isnan(untimed.vel_east_mps) && std::isnan(untimed.vel_var_m2ps2));
    const localize::Estimate after_gap = l.step(no_frame(6, 8, 104.0));
    EXPECT_TRUE(std::isnan(after_gap.vel_east_mps)) << "the previous step had no time";
    const localize::Estimate backwards = l.step(no_frame(6, 8, 103.0));
    EXPECT_TRUE(std::isnan(backwards.vel_east_mps)) << "time running backwards gives no velocity";
}

TEST(Uncertainty, LatitudeLongitudeFromTheMapOrigin) {
    LocalizerOnTestWorld run;
    run.config.map_origin = sim::GeoOrigin{41.039017, -83.308825};
    localize::Localizer l = run.make();
    const localize::Estimate e = l.step(no_frame(0, 0, NAN));
    sim::Map frame;
    frame.metres_per_pixel = l.metres_per_pixel(), frame.origin = run.config.map_origin;
    const sim::LatLon want = sim::map_pixel_to_latlon(frame, e.x, e.y);
    EXPECT_DOUBLE_EQ(e.latitude_deg, want.latitude_deg);
    EXPECT_DOUBLE_EQ(e.longitude_deg, want.longitude_deg);
    EXPECT_LT(e.latitude_deg, 41.039017) << "the map's y points south";
    run.config.map_origin = sim::GeoOrigin{95, 0};
    EXPECT_THROW(run.make(), Error);
}

TEST(Uncertainty, ErrorInSigmasAndTheGaussianShares) {
    // A 4 m north by 2 m east ellipse: 4 m north is one sigma, 4 m east two.
    EXPECT_DOUBLE_EQ(localize::error_in_sigmas(0, 4, 16, 0, 4), 1);
    EXPECT_DOUBLE_EQ(localize::error_in_sigmas(4, 0, 16, 0, 4), 2);
    // Correlated: along the long axis (1, 1)/sqrt2 of [[5, 3], [3, 5]] (eigenvalue 8).
    EXPECT_NEAR(localize::error_in_sigmas(2, 2, 5, 3, 5), 1, 1e-12);
    EXPECT_TRUE(std::isinf(localize::error_in_sigmas(1, 0, 0, 0, 0)));
    EXPECT_EQ(localize::error_in_sigmas(0, 0, 0, 0, 0), 0);
    EXPECT_NEAR(localize::gaussian_inside(1), 0.3935, 1e-4);
    EXPECT_NEAR(localize::gaussian_inside(2), 0.8647, 1e-4);
}

TEST(Uncertainty, ASimulatedFlightReportsItsCalibration) {
    const std::unique_ptr<Backend> backend = default_registry().create("cpu");
    localize::LocalizerConfig lc;
    localize::Localizer localizer(test_world().map.image.view(), test_world().map.metres_per_pixel, *backend, lc);
    SimulatedFlightSource source(test_world().world, short_flight(12), 5);
    const localize::LocalizationResult r = localize::run_localization(source, localizer);
    std::size_t in1 = 0, in2 = 0, judged = 0;
    for (const localize::LocalizationRow& row : r.rows) {
        ASSERT_TRUE(std::isfinite(row.error_sigmas)) << "every simulated step has truth";
        const double east = (row.estimate_x - row.truth_x) * localizer.metres_per_pixel();
        const double north = -(row.estimate_y - row.truth_y) * localizer.metres_per_pixel();
        EXPECT_NEAR(row.error_sigmas, localize::error_in_sigmas(east, north, row.cov_nn_m2, row.cov_ne_m2, row.cov_ee_m2), 1e-12);
        ++judged, in1 += row.error_sigmas <= 1, in2 += row.error_sigmas <= 2;
    }
    ASSERT_GT(judged, 0u);
    EXPECT_DOUBLE_EQ(r.summary.inside_1sigma, double(in1) / judged);
    EXPECT_DOUBLE_EQ(r.summary.inside_2sigma, double(in2) / judged);
    EXPECT_LE(r.summary.inside_1sigma, r.summary.inside_2sigma);
    std::cout << "simulated FR-200, 12 s: truth inside 1 sigma " << 100 * r.summary.inside_1sigma << " %, 2 sigma "
              << 100 * r.summary.inside_2sigma << " %\n";
}

}  // namespace
}  // namespace trn::filter::testing
