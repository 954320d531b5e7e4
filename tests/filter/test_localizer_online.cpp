// Issue 43 item 4: the online Localizer as an integrator meets it. The defaults have one home
// (localizer_defaults.hpp) and its compass-less rules run inside the Localizer; a re-anchor on a new
// fix starts the filter over there with the configuration kept; and the traps of the issue are
// refused with an error naming the input in user terms.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "filter_test_world.hpp"
#include "trn/error.hpp"
#include "trn/io/image_io.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"

namespace trn::filter::testing {
namespace {

struct Online {
    std::unique_ptr<Backend> backend = default_registry().create("cpu");
    localize::LocalizerConfig config = localize::localizer_profile(Profile::Ours);
    Online() { config.start_x = 400, config.start_y = 400, config.start_heading_rad = 0; }
    localize::Localizer make() const {
        return localize::Localizer(test_world().map.image.view(), test_world().map.metres_per_pixel, *backend, config);
    }
};

// A 160x120 view of the world (the camera's, two years after the map) centred on (x, y), north up.
GrayImage frame_at(double x, double y) {
    const GrayImage& w = test_world().world.image;
    GrayImage f;
    f.width = 160, f.height = 120;
    f.pixels.resize(160 * 120);
    for (int r = 0; r < f.height; ++r)
        for (int c = 0; c < f.width; ++c) f.pixels[r * f.width + c] = w.pixels[(int(y) - 60 + r) * w.width + int(x) - 80 + c];
    return f;
}

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(LocalizerDefaults, OneHomeWithTheCliValues) {
    const localize::LocalizerConfig ours = localize::localizer_profile(Profile::Ours);
    EXPECT_EQ(ours.filter.init_radius_m, localize::kHandoverInitRadiusM);
    EXPECT_EQ(ours.compassless_max_particles, localize::kCompasslessUniformMaxParticles);
    EXPECT_EQ(ours.compassless_yaw_sd_deg, localize::kCompasslessYawSdDeg);
    const localize::LocalizerConfig d = localize::dissertation_profile();
    EXPECT_EQ(d.filter.init_radius_m, 300);
    EXPECT_EQ(d.compassless_max_particles, 0u) << "the dissertation has no compass-less mode to raise";
    // LocalizerConfig{} stays the plain struct (the studies' and tests' own settings).
    EXPECT_EQ(localize::LocalizerConfig{}.compassless_max_particles, 0u);
}

TEST(LocalizerDefaults, CompasslessRulesResolvedInTheLibrary) {
    localize::LocalizerConfig c = localize::localizer_profile(Profile::Ours);
    c.filter.heading = HeadingMode::None;
    EXPECT_EQ(localize::resolved_config(c).filter.max_particles, 6000u) << "uniform yaw prior";
    c.start_heading_rad = 1;
    EXPECT_EQ(localize::resolved_config(c).filter.max_particles, 2000u) << "a yaw prior";
    EXPECT_EQ(localize::resolved_config(c).filter.init_heading_sd_deg, 10);
    c.filter.init_heading_sd_deg = 4;
    EXPECT_EQ(localize::resolved_config(c).filter.init_heading_sd_deg, 4) << "a spread given is kept";
    c.filter.heading = HeadingMode::Compass, c.start_heading_rad = NAN;
    EXPECT_EQ(localize::resolved_config(c).filter.max_particles, 2000u) << "a compass needs no wider set";
    // The Localizer runs the resolved config.
    Online run;
    run.config.filter.heading = HeadingMode::None, run.config.start_heading_rad = NAN;
    localize::Localizer l = run.make();
    localize::Observation o;
    o.odometry_east_m = o.odometry_north_m = 0;
    EXPECT_EQ(l.step(o).particles, 6000u);
    EXPECT_EQ(l.config().filter.max_particles, 6000u);
}

TEST(LocalizerReanchor, StartsOverAroundTheFixKeepingTheConfig) {
    Online run;
    localize::Localizer l = run.make();
    localize::Observation o;
    o.odometry_east_m = 2, o.odometry_north_m = 0, o.heading_rad = 0, o.map_px_per_camera_px = 1;
    for (int i = 0; i < 3; ++i) {
        const GrayImage f = frame_at(400 + 2 * i / test_world().map.metres_per_pixel, 400);
        o.frame = f.view();
        l.step(o);
    }
    const double mpp = test_world().map.metres_per_pixel;
    l.reanchor(600, 250, 20);
    const GrayImage f = frame_at(600, 250);
    o.frame = f.view(), o.odometry_east_m = 0;
    const localize::Estimate e = l.step(o);
    EXPECT_LT(std::hypot(e.x - 600, e.y - 250) * mpp, 20) << "the estimate is at the new fix";
    EXPECT_EQ(std::string(localize::lock_state_name(e.lock)), "unknown") << "no fix vouches for the new place yet";
    EXPECT_FALSE(e.reinitialised);
    EXPECT_TRUE(std::isnan(e.vel_north_mps)) << "no velocity across the jump";
    EXPECT_EQ(l.config().filter.init_radius_m, localize::kHandoverInitRadiusM) << "the configuration is kept";
    // Refused: off the map (naming its size), a radius that is not one.
    EXPECT_NE(message_of([&] { l.reanchor(-5000, 400, 20); }).find("px map"), std::string::npos);
    EXPECT_NE(message_of([&] { l.reanchor(600, 250, 0); }).find("radius_m"), std::string::npos);
}

TEST(LocalizerReanchor, WithoutACompassKeepsTheLearntYaw) {
    Online run;
    run.config.filter.heading = HeadingMode::None, run.config.start_heading_rad = 1.0;
    localize::Localizer l = run.make();
    localize::Observation o;
    o.odometry_east_m = o.odometry_north_m = 0, o.odometry_yaw_rad = 0;
    const double yaw = l.step(o).yaw;
    l.reanchor(600, 600, 30);
    const localize::Estimate e = l.step(o);
    EXPECT_NEAR(std::remainder(e.yaw - yaw, 2 * M_PI), 0, 0.2) << "a fix tells the position, not the heading";
}

TEST(LocalizerTraps, RefusedNamingTheInputInUserTerms) {
    Online run;
    const double mpp = test_world().map.metres_per_pixel;
    const int w = test_world().map.image.width, h = test_world().map.image.height;
    // A start off the map, naming the map's size.
    run.config.start_x = 1e6;
    EXPECT_NE(message_of([&] { run.make(); }).find(std::to_string(w) + "x" + std::to_string(h) + " px map"), std::string::npos);
    run.config.start_x = 400;
    // A field of view outside [5, 170] degrees (1.2: radians).
    run.config.camera_hfov_deg = 1.2;
    const std::string hfov = message_of([&] { run.make(); });
    EXPECT_NE(hfov.find("camera_hfov_deg"), std::string::npos);
    EXPECT_NE(hfov.find("radians?"), std::string::npos);
    run.config.camera_hfov_deg = 171;
    EXPECT_NE(message_of([&] { run.make(); }).find("[5, 170]"), std::string::npos);
    run.config.camera_hfov_deg = 60;
    localize::Localizer l = run.make();
    const GrayImage f = frame_at(400, 400);
    localize::Observation o;
    o.frame = f.view(), o.heading_rad = 0, o.odometry_east_m = o.odometry_north_m = 0;
    // Both the scale and the altitude: which wins is ambiguous.
    o.map_px_per_camera_px = 1, o.altitude_agl_m = 100;
    EXPECT_NE(message_of([&] { l.step(o); }).find("ambiguous"), std::string::npos);
    // The attitude in degrees.
    o.altitude_agl_m = NAN, o.has_attitude = true, o.roll_rad = 5, o.pitch_rad = 12;
    EXPECT_NE(message_of([&] { l.step(o); }).find("radians"), std::string::npos);
    o.has_attitude = false;
    // No internals in the scale's error (template_scale, map_px_per_camera_px).
    o.map_px_per_camera_px = NAN, o.altitude_agl_m = -3;
    const std::string altitude = message_of([&] { l.step(o); });
    EXPECT_NE(altitude.find("altitude_agl_m"), std::string::npos);
    EXPECT_EQ(altitude.find("template_scale"), std::string::npos);
    // Odometry of the other heading mode.
    o.altitude_agl_m = NAN, o.map_px_per_camera_px = 1, o.odometry_yaw_rad = 0.1;
    EXPECT_NE(message_of([&] { l.step(o); }).find("heading \"none\""), std::string::npos);
    o.odometry_yaw_rad = NAN;
    EXPECT_GT(l.step(o).particles, 0u) << "the same step without the traps runs";
    (void)mpp;
}

TEST(LocalizerTraps, CompassModeWithoutAnyHeadingAndCompasslessWithOne) {
    Online run;
    run.config.start_heading_rad = NAN;
    localize::Localizer compass = run.make();
    localize::Observation o;
    o.odometry_east_m = o.odometry_north_m = 0;
    EXPECT_NO_THROW(compass.step(o)) << "a step without a frame needs no heading";
    const GrayImage f = frame_at(400, 400);
    o.frame = f.view(), o.map_px_per_camera_px = 1;
    EXPECT_NE(message_of([&] { compass.step(o); }).find("start_heading_rad"), std::string::npos);
    o.heading_rad = 0.5;
    EXPECT_NO_THROW(compass.step(o)) << "a step with a heading scores";
    o.heading_rad = NAN;
    EXPECT_NO_THROW(compass.step(o)) << "a later step may lack one (a dropout)";
    o.frame = {}, o.map_px_per_camera_px = NAN;
    run.config.filter.heading = HeadingMode::None;
    localize::Localizer none = run.make();
    o.heading_rad = 0.5;
    EXPECT_NE(message_of([&] { none.step(o); }).find("previous frame's axes"), std::string::npos);
}

}  // namespace
}  // namespace trn::filter::testing
