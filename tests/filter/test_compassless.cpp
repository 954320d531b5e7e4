// Compass-less localization (issue 25 part 2): yaw in each particle's state, turned by the
// odometry's rotation increment. The filter must converge on a simulated flight from a uniform
// yaw prior, count (x, y, yaw) KLD bins, and keep the motion model's frames straight.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "filter_test_world.hpp"
#include "trn/detail/angles.hpp"
#include "trn/error.hpp"
#include "trn/filter/motion_model.hpp"
#include "trn/filter/particle_filter.hpp"
#include "trn/filter/visual_odometry.hpp"
#include "trn/localize/localization.hpp"

namespace trn::filter {
namespace {

using testing::short_flight;
using testing::test_world;

FilterConfig compassless_config(std::uint64_t seed = 1) {
    FilterConfig c;
    c.seed = seed;
    c.heading = HeadingMode::None;
    c.init_radius_m = 20;
    c.max_particles = 2000;
    return c;
}

localize::LocalizationResult run_compassless(const FilterConfig& cfg, FlightSource& source, double start_yaw_rad = NAN) {
    const std::unique_ptr<Backend> backend = default_registry().create("cpu");
    localize::LocalizerConfig lc;
    lc.filter = cfg;
    lc.start_heading_rad = start_yaw_rad;
    localize::Localizer localizer(test_world().map.image.view(), test_world().map.metres_per_pixel, *backend, lc);
    return localize::run_localization(source, localizer);
}

// A scorer that gives every pose the same score: steps are pure propagation.
class FlatScorer : public ParticleScorer {
public:
    void score(GrayView, double, std::span<const Pose> poses, std::span<ParticleScore> out, PhaseTimes*) override {
        for (std::size_t i = 0; i < poses.size(); ++i) out[i] = {0.5f, 0.5f, 0.0f, 100, kScoreValid};
    }
};

TEST(Compassless, MotionTurnsByTheIncrementAndMovesInTheParticlesOwnFrame) {
    MotionModel model;
    // 10 m forward and 2 m right of the previous frame's top, turned 30 degrees since.
    const StepMotion m = make_yaw_state_motion(2, 10, 30 * kDeg, 1.0);
    EXPECT_TRUE(m.yaw_state);
    EXPECT_FALSE(m.have_heading);
    const std::array<double, 5> none{};
    for (const double yaw0 : {0.0, 90 * kDeg, -135 * kDeg}) {
        double x = 100, y = 100, yaw = yaw0;
        propagate_particle(model, m, 1.0, none, x, y, yaw);
        // Forward along the old yaw, right 90 degrees clockwise of it (x east, y south).
        EXPECT_NEAR(x, 100 + 10 * std::sin(yaw0) + 2 * std::cos(yaw0), 1e-9);
        EXPECT_NEAR(y, 100 - 10 * std::cos(yaw0) + 2 * std::sin(yaw0), 1e-9);
        EXPECT_NEAR(wrap_angle(yaw - yaw0), 30 * kDeg, 1e-12);
    }
    // Unknown rotation: no turn, yaw_unknown_sd_deg of noise; known: yaw_sd_deg + yaw_turn_sd per radian.
    const std::array<double, 5> yaw_noise{1, 0, 0, 0, 0};
    double x = 0, y = 0, yaw = 0;
    propagate_particle(model, make_yaw_state_motion(0, 0, NAN, 1.0), 1.0, yaw_noise, x, y, yaw);
    EXPECT_NEAR(yaw, model.yaw_unknown_sd_deg * kDeg, 1e-12);
    yaw = 0;
    propagate_particle(model, make_yaw_state_motion(0, 0, 1.0, 1.0), 1.0, yaw_noise, x, y, yaw);
    EXPECT_NEAR(yaw, 1.0 + model.yaw_sd_deg * kDeg + model.yaw_turn_sd, 1e-12);
}

TEST(Compassless, UniformPriorSpreadsYawAllAroundAndAGaussianOneStaysNarrow) {
    FlatScorer scorer;
    ParticleFilter uniform(scorer, compassless_config());
    uniform.initialise(300, 300, NAN);
    std::vector<int> quadrant(4);
    for (const Particle& p : uniform.particles()) ++quadrant[static_cast<int>(std::floor((p.yaw + kPi) / (kPi / 2))) & 3];
    for (int q : quadrant) EXPECT_GT(q, 400) << "a uniform prior fills every quadrant (2000 particles)";
    EXPECT_GT(uniform.estimate().yaw_sd, 2.0) << "circular sd of uniform yaws is large";

    FilterConfig g = compassless_config();
    g.init_heading_sd_deg = 5;
    ParticleFilter gaussian(scorer, g);
    gaussian.initialise(300, 300, 1.0);
    EXPECT_NEAR(gaussian.estimate().yaw, 1.0, 0.01);
    EXPECT_NEAR(gaussian.estimate().yaw_sd / kDeg, 5.0, 0.5);
}

TEST(Compassless, KldBinsCountYawSoTheBinCountGrowsWithTheYawSpread) {
    FlatScorer scorer;
    auto bins_after_one_step = [&](HeadingMode mode, double yaw_sd_deg) {
        FilterConfig c = compassless_config();
        c.heading = mode;
        c.max_particles = 5000;
        c.init_radius_m = 5;  // a few position bins
        c.init_heading_sd_deg = yaw_sd_deg;
        ParticleFilter pf(scorer, c);
        pf.initialise(300, 300, std::isnan(yaw_sd_deg) ? NAN : 0.0);
        FilterInput in;  // no frame: propagation only
        in.odometry_east_m = in.odometry_north_m = 0;
        in.odometry_yaw_rad = 0;
        in.heading_rad = NAN;
        return pf.step(in).occupied_bins;
    };
    const std::size_t narrow = bins_after_one_step(HeadingMode::None, 1), wide = bins_after_one_step(HeadingMode::None, 60),
                      uniform = bins_after_one_step(HeadingMode::None, NAN), compass = bins_after_one_step(HeadingMode::Compass, NAN);
    std::printf("occupied bins: yaw sd 1 deg %zu, 60 deg %zu, uniform %zu; compass mode (uniform yaws, x-y bins) %zu\n", narrow, wide,
                uniform, compass);
    EXPECT_GT(wide, 4 * narrow);
    EXPECT_GT(uniform, wide);
    EXPECT_LT(compass, narrow + 10) << "with a compass the bins are x-y only";
}

TEST(Compassless, SimulatedFlightWithoutCompassConvergesFromAUniformYawPrior) {
    // FR-200-wind: the camera points up to 30 degrees off the course, so the direction of travel
    // would be a wrong heading; the odometry's own yaw (truth + its heading error) only turns the particles.
    sim::FlightConfig flight = short_flight(40);
    flight.scenario = sim::find_scenario("FR-200-wind");
    SimulatedFlightSource src(test_world().world, flight, 10);
    const localize::LocalizationResult r = run_compassless(compassless_config(), src);
    ASSERT_EQ(r.rows.size(), 200u);
    EXPECT_EQ(r.run.heading, "none");
    const localize::LocalizationSummary& s = r.summary;
    std::printf("no compass: converged from frame %.0f, mean error since %.2f m, yaw error since %.2f deg, final yaw sd %.2f deg; "
                "odometry mean %.2f m\n",
                s.converged_from_frame, s.converged_mean_error_m, s.converged_mean_yaw_error_deg, s.final_yaw_sd_deg, s.odometry_mean_error_m);
    ASSERT_TRUE(std::isfinite(s.converged_from_frame)) << "the yaw spread must fall below 10 degrees";
    EXPECT_LT(s.converged_from_frame, 500) << "within the first 10 s";
    EXPECT_LT(s.converged_mean_error_m, 5.0);
    EXPECT_LT(s.converged_mean_yaw_error_deg, 3.0);
    EXPECT_LT(s.final_yaw_sd_deg, 5.0);
    EXPECT_LT(std::abs(r.rows.back().estimate_yaw - r.rows.back().truth_yaw), 3 * kDeg);
}

TEST(Compassless, VisualOdometryOwnYawFollowsTheTrueTurns) {
    // FC-200: a circle, the camera turns all the time; the VO's yaw changes must be the truth's.
    sim::FlightConfig flight = short_flight(8);
    flight.scenario = sim::find_scenario("FC-200");
    SimulatedFlightSource sim(test_world().world, flight, 10);
    VisualOdometrySource vo(sim, test_world().world.metres_per_pixel, {}, true);
    FlightSample s;
    double prev_vo = NAN, prev_truth = NAN, worst = 0, turned = 0;
    while (vo.next(s)) {
        ASSERT_TRUE(std::isfinite(s.odometry_yaw_rad)) << s.odometry_source;
        if (std::isfinite(prev_vo)) {
            const double truth = wrap_angle(s.truth_yaw - prev_truth);
            worst = std::max(worst, std::abs(wrap_angle(s.odometry_yaw_rad - prev_vo) - truth));
            turned += std::abs(truth);
        }
        prev_vo = s.odometry_yaw_rad, prev_truth = s.truth_yaw;
    }
    std::printf("turned %.1f deg, worst VO rotation error %.3f deg per step\n", turned / kDeg, worst / kDeg);
    EXPECT_GT(turned, 10 * kDeg);
    EXPECT_LT(worst, 0.3 * kDeg);
}

TEST(Compassless, BadYawSettingsAreNamed) {
    FlatScorer scorer;
    FilterConfig c = compassless_config();
    c.kld_yaw_bin_deg = 0;
    try {
        ParticleFilter pf(scorer, c);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("kld_yaw_bin_deg"), std::string::npos) << e.what();
    }
    c = compassless_config();
    c.motion.yaw_sd_deg = -1;
    try {
        ParticleFilter pf(scorer, c);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("yaw_sd_deg"), std::string::npos) << e.what();
    }
    EXPECT_EQ(parse_heading_mode("none"), HeadingMode::None);
    EXPECT_THROW(parse_heading_mode("north"), Error);
}

}  // namespace
}  // namespace trn::filter
