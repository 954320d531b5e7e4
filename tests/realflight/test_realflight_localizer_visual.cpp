// Issue 43 item 4: visual odometry online. On the real flight (the 16 frames as an AIR folder), the
// online Localizer with LocalizerConfig::visual_odometry, fed the rows as a robot would (frames as
// taken, altitude, attitude, heading) but NO odometry, computes the odometry from the frames and
// gives `trnkit localize --odometry visual`'s estimates: bit for bit against the library's
// whole-flight run, to the CSV's 10 digits against the CLI; with a compass and without one.
// Skipped (visibly) without the shared data.
#include <sstream>

#include "real_air_fixture.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/localize/air_inputs.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/registry.hpp"

namespace trn::test {
namespace {

class RealFlightVisualOdometryOnline : public RealAirFolder, public testing::WithParamInterface<const char*> {};

TEST_P(RealFlightVisualOdometryOnline, LocalizerComputesTheCliVisualOdometry) {
    const bool compass = std::string(GetParam()) == "compass";
    localize::AirInputOptions io;
    io.dataset = dir_, io.map = map();
    const localize::AirInputs in = localize::resolve_air_inputs(io);
    const double mpp = in.map.metres_per_pixel;
    // What `trnkit localize --init-radius-m 50 --seed 1 [--heading none --max-particles 3000]` sets.
    localize::LocalizerConfig config = localize::localizer_profile(filter::Profile::Ours);
    config.filter.init_radius_m = 50, config.filter.seed = 1;
    if (!compass) {
        config.filter.heading = filter::HeadingMode::None, config.filter.init_heading_sd_deg = NAN;
        config.filter.max_particles = 3000, config.compassless_max_particles = 0;
    }

    // The CLI and the library's whole-flight run, odometry visual.
    const std::string out = dir_ + "/cli";
    const auto cli = run_trnkit("localize --dataset " + dir_ + " --map " + map() + " --rate 0.5 --no-plots --backend cpu --init-radius-m 50 "
                                "--seed 1 --odometry visual --out " + out + (compass ? "" : " --heading none --max-particles 3000"));
    ASSERT_EQ(cli.code, 0) << cli.output;
    const auto cli_rows = csv(out + "/localization.csv");
    std::unique_ptr<Backend> batch_backend = default_registry().create("cpu"), online_backend = default_registry().create("cpu");
    localize::LocalizationSpec spec;
    spec.flight = localize::AirFolderFlight{dir_, in.camera, in.fps};
    spec.rate_hz = 0.5;
    spec.odometry = localize::OdometryKind::Visual;
    spec.localizer = config;
    const localize::LocalizationResult batch = localize::run_localization(spec, in.map.image.view(), mpp, *batch_backend);
    ASSERT_EQ(batch.rows.size(), 16u);
    ASSERT_EQ(cli_rows.size(), batch.rows.size());

    // The online Localizer: no odometry given, visual_odometry on.
    localize::AirFrameReader reader(dir_);
    localize::AirFrame frame;
    std::unique_ptr<localize::Localizer> online;
    std::size_t step = 0, visual_steps = 0;
    while (reader.next(frame)) {
        if (!online) {
            localize::LocalizerConfig c = config;
            c.start_x = frame.truth_x, c.start_y = frame.truth_y, c.camera_hfov_deg = in.camera.hfov_deg;
            c.visual_odometry = true;
            online = std::make_unique<localize::Localizer>(in.map.image.view(), mpp, *online_backend, c);
        }
        localize::Observation o = compass ? frame.observation() : frame.observation_without_compass();
        o.odometry_east_m = o.odometry_north_m = o.odometry_yaw_rad = NAN;
        const localize::Estimate e = online->step(o);
        ASSERT_LT(step, batch.rows.size());
        const localize::LocalizationRow& r = batch.rows[step];
        EXPECT_EQ(e.x, r.estimate_x) << "step " << step;
        EXPECT_EQ(e.y, r.estimate_y) << "step " << step;
        EXPECT_EQ(e.yaw, r.estimate_yaw) << "step " << step;
        EXPECT_EQ(e.particles, r.particles) << "step " << step;
        EXPECT_EQ(std::string(e.odometry_source), r.odometry_source) << "step " << step;
        EXPECT_EQ(cli_rows[step].at("estimate_x"), ten_digits(e.x)) << "step " << step;
        EXPECT_EQ(cli_rows[step].at("estimate_y"), ten_digits(e.y)) << "step " << step;
        EXPECT_EQ(cli_rows[step].at("odometry_source"), e.odometry_source) << "step " << step;
        visual_steps += std::string(e.odometry_source) == "visual:features" || std::string(e.odometry_source) == "visual:phase";
        ++step;
    }
    EXPECT_EQ(step, batch.rows.size());
    EXPECT_GE(visual_steps, 10u) << "the visual odometry found too few steps to test anything";
    std::cout << GetParam() << ": " << step << " steps identical (CLI --odometry visual, library, online), " << visual_steps
              << " by visual odometry; filter mean error " << batch.summary.filter_mean_error_m << " m\n";
}

INSTANTIATE_TEST_SUITE_P(Heading, RealFlightVisualOdometryOnline, testing::Values("compass", "none"));

}  // namespace
}  // namespace trn::test
