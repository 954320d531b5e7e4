// Issue 43 item 4: visual odometry online. A Localizer with LocalizerConfig::visual_odometry, fed a
// simulated flight's frames with no odometry, computes the odometry from the frames by
// filter::VisualOdometryTrack and gives run_localization's --odometry visual estimates bit for bit
// (with and without a compass); odometry the caller gives is used as given (the documented rule),
// and each estimate says which odometry it used.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "filter_test_world.hpp"
#include "trn/error.hpp"
#include "trn/filter/flight_source.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"

namespace trn::filter::testing {
namespace {

localize::LocalizerConfig small_config(bool compass) {
    localize::LocalizerConfig c = localize::localizer_profile(Profile::Ours);
    c.filter.max_particles = 300, c.filter.min_particles = 100, c.compassless_max_particles = 0;
    c.filter.init_radius_m = 20;
    if (!compass) c.filter.heading = HeadingMode::None, c.filter.init_heading_sd_deg = NAN;
    return c;
}

class LocalizerVisualOdometry : public ::testing::TestWithParam<bool> {};

TEST_P(LocalizerVisualOdometry, OnlineEqualsTheWholeFlightRunOnASimulatedFlight) {
    const bool compass = GetParam();
    const TestWorld& w = test_world();
    const sim::FlightConfig flight = short_flight(8);
    const std::size_t stride = 10;
    auto batch_backend = default_registry().create("cpu"), online_backend = default_registry().create("cpu");
    localize::LocalizationSpec spec;
    spec.flight = localize::SimulatedFlight{&w.world, flight};
    spec.odometry = localize::OdometryKind::Visual;
    spec.rate_hz = flight.scenario.fps / stride;
    spec.localizer = small_config(compass);
    const localize::LocalizationResult batch = localize::run_localization(spec, w.map, *batch_backend);
    ASSERT_GE(batch.rows.size(), 4u);

    SimulatedFlightSource source(w.world, flight, stride);
    FlightSample s;
    std::unique_ptr<localize::Localizer> online;
    std::size_t step = 0;
    while (source.next(s)) {
        if (!online) {
            localize::LocalizerConfig c = small_config(compass);
            c.start_x = s.truth_x, c.start_y = s.truth_y, c.visual_odometry = true;
            if (compass) c.start_heading_rad = s.heading_rad;
            online = std::make_unique<localize::Localizer>(w.map.image.view(), w.map.metres_per_pixel, *online_backend, c, w.map.valid_view());
        }
        localize::Observation o;  // no odometry: the frame's own
        if (!s.image.pixels.empty()) o.frame = s.image.view();
        o.map_px_per_camera_px = s.map_px_per_camera_px;
        if (compass) o.heading_rad = s.heading_rad;
        o.time_s = s.time_s;
        const localize::Estimate e = online->step(o);
        ASSERT_LT(step, batch.rows.size());
        EXPECT_EQ(e.x, batch.rows[step].estimate_x) << "step " << step;
        EXPECT_EQ(e.y, batch.rows[step].estimate_y) << "step " << step;
        EXPECT_EQ(e.yaw, batch.rows[step].estimate_yaw) << "step " << step;
        EXPECT_EQ(std::string(e.odometry_source), batch.rows[step].odometry_source) << "step " << step;
        EXPECT_EQ(std::string(e.odometry_source), step == 0 ? "visual:start" : "visual:features") << "step " << step;
        ++step;
    }
    EXPECT_EQ(step, batch.rows.size());
}

INSTANTIATE_TEST_SUITE_P(Compass, LocalizerVisualOdometry, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? std::string("compass") : std::string("none"); });

// The rule: the frame's odometry only when the step gives none; odometry given is used as given,
// so with it the estimates are those of a Localizer without visual odometry, bit for bit.
TEST(LocalizerVisualOdometryRule, OdometryGivenIsUsedAsGiven) {
    const TestWorld& w = test_world();
    SimulatedFlightSource source(w.world, short_flight(6), 10);
    auto backend = default_registry().create("cpu");
    localize::LocalizerConfig off = small_config(true);
    EXPECT_FALSE(off.visual_odometry);  // the default (kDefaultVisualOdometry)
    EXPECT_EQ(off.visual_odometry, localize::kDefaultVisualOdometry);
    std::vector<FlightSample> samples;
    for (FlightSample s; source.next(s);) samples.push_back(s);
    ASSERT_GE(samples.size(), 4u);
    off.start_x = samples[0].truth_x, off.start_y = samples[0].truth_y, off.start_heading_rad = samples[0].heading_rad;
    localize::LocalizerConfig on = off;
    on.visual_odometry = true;
    localize::Localizer with(w.map.image.view(), w.map.metres_per_pixel, *backend, on);
    localize::Localizer without(w.map.image.view(), w.map.metres_per_pixel, *backend, off);
    double prev_e = 0, prev_n = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const FlightSample& s = samples[i];
        localize::Observation o;
        o.frame = s.image.view();
        o.map_px_per_camera_px = s.map_px_per_camera_px;
        o.heading_rad = s.heading_rad;
        o.odometry_east_m = s.odometry_east_m - prev_e, o.odometry_north_m = s.odometry_north_m - prev_n;  // the simulator's
        prev_e = s.odometry_east_m, prev_n = s.odometry_north_m;
        if (i == samples.size() - 1) o.odometry_east_m = NAN;  // none given: the frame's own, visual odometry off: none
        const localize::Estimate a = with.step(o), b = without.step(o);
        if (i + 1 < samples.size()) {
            EXPECT_STREQ(a.odometry_source, "given");
            EXPECT_STREQ(b.odometry_source, "given");
            EXPECT_EQ(a.x, b.x) << "step " << i;
            EXPECT_EQ(a.y, b.y) << "step " << i;
            EXPECT_EQ(a.yaw, b.yaw) << "step " << i;
        } else {
            EXPECT_STREQ(a.odometry_source, "visual:features");  // tracked all along: ready at once
            EXPECT_FALSE(a.odometry_lost);
            EXPECT_STREQ(b.odometry_source, "none");
            EXPECT_TRUE(b.odometry_lost);
        }
    }
}

// A frame too small to track is refused naming the option, not failed deep in the tracker.
TEST(LocalizerVisualOdometryRule, TooSmallAFrameIsRefusedNamingTheOption) {
    const TestWorld& w = test_world();
    auto backend = default_registry().create("cpu");
    localize::LocalizerConfig c = small_config(true);
    c.start_x = c.start_y = 400, c.start_heading_rad = 0, c.visual_odometry = true;
    localize::Localizer loc(w.map.image.view(), w.map.metres_per_pixel, *backend, c);
    const GrayImage& world = w.world.image;
    localize::Observation o;
    o.frame = GrayView{world.pixels.data(), 12, 12, world.width};
    o.map_px_per_camera_px = 1, o.heading_rad = 0;
    try {
        loc.step(o);
        FAIL() << "a 12x12 frame was tracked";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("visual_odometry"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("12x12"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace trn::filter::testing
