// The particle filter on a real backend and simulated flights: it must track, reproduce a seeded
// run exactly, keep the sampling counts its method promises and survive bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "filter_test_world.hpp"
#include "trn/error.hpp"
#include "trn/filter/particle_filter.hpp"
#include "trn/detail/angles.hpp"
#include "trn/localize/localization.hpp"

namespace trn::filter {
namespace {

using testing::short_flight;
constexpr double kHalfPi = 1.5707963267948966;
using testing::test_world;
using localize::LocalizationResult;
using localize::LocalizationRow;

struct Rig {
    std::unique_ptr<Backend> backend = default_registry().create("cpu");
    BackendScorer scorer{*backend, test_world().map.image.view()};
};

FilterConfig small_config(std::uint64_t seed = 1) {
    FilterConfig c;
    c.seed = seed;
    c.init_radius_m = 20;  // short flights: start close, so the run is about tracking
    c.max_particles = 600;
    c.fixed_particles = 300;
    return c;
}

// A whole flight through the Localizer, as every front end runs one.
LocalizationResult localize_flight(FlightSource& source, const FilterConfig& cfg, double start_x = NAN, double start_y = NAN,
                                   double start_heading_rad = NAN) {
    const std::unique_ptr<Backend> backend = default_registry().create("cpu");
    localize::LocalizerConfig lc;
    lc.filter = cfg;
    lc.start_x = start_x, lc.start_y = start_y, lc.start_heading_rad = start_heading_rad;
    localize::Localizer localizer(test_world().map.image.view(), test_world().map.metres_per_pixel, *backend, lc);
    return localize::run_localization(source, localizer);
}

LocalizationResult run_flight(const FilterConfig& cfg, const sim::FlightConfig& flight, double start_x = NAN, double start_y = NAN) {
    SimulatedFlightSource src(test_world().world, flight, 10);
    return localize_flight(src, cfg, start_x, start_y);
}

LocalizationResult run(const FilterConfig& cfg, double seconds, std::uint64_t flight_seed = 5) {
    return run_flight(cfg, short_flight(seconds, flight_seed));
}

TEST(ParticleFilter, TracksTheAircraftBetterThanOdometry) {
    const LocalizationResult r = run(small_config(), 30);
    ASSERT_EQ(r.rows.size(), 150u);
    EXPECT_LT(r.rows.back().error_m, 10.0);
    EXPECT_LT(r.summary.filter_final_error_m, 0.5 * r.summary.odometry_final_error_m);
    EXPECT_LT(r.summary.filter_mean_error_m, r.summary.odometry_mean_error_m);
    EXPECT_EQ(r.summary.counters.reinitialisations, 0u);
    EXPECT_EQ(r.summary.counters.lock_lost_events, 0u) << "a good lock must not be declared lost";
}

TEST(ParticleFilter, TracksACrabbingClimbingFlightBetterThanOdometry) {
    // FR-200-wind: the camera points up to 30 degrees off the course, the altitude swings +-30 %
    // and the template scale comes from a noisy barometer.
    sim::FlightConfig flight = short_flight(20);
    flight.scenario = sim::find_scenario("FR-200-wind");
    const LocalizationResult r = run_flight(small_config(), flight);
    ASSERT_EQ(r.rows.size(), 100u);
    EXPECT_LT(r.summary.filter_mean_error_m, 0.5 * r.summary.odometry_mean_error_m);
    EXPECT_LT(r.rows.back().error_m, 10.0);
    // Without the crab offset (distance along the heading, --motion-along-heading) it is pulled off the track.
    FilterConfig along = small_config();
    along.motion.along_heading = true;
    const LocalizationResult l = run_flight(along, flight);
    EXPECT_LT(r.summary.filter_mean_error_m, l.summary.filter_mean_error_m);
}

// A scorer with a known landscape (map pixels = metres): the true place is a clear peak (0.9),
// a decoy 50 m south of it a mediocre one (0.3: contrast ~2.3 against the texture), everywhere else scores 0.1 +- 0.1 like random
// texture. Both move with the aircraft, as a wrong lock tracks along with the odometry.
class LandscapeScorer : public ParticleScorer {
public:
    double truth_x = 1000, truth_y = 1000;
    static constexpr double kDecoySouth = 50;
    void score(GrayView, double, std::span<const Pose> poses, std::span<ParticleScore> out, PhaseTimes*) override {
        for (std::size_t i = 0; i < poses.size(); ++i) {
            const double x = poses[i].x, y = poses[i].y;
            auto h = static_cast<std::uint64_t>(std::llround(x / 3) * 73856093 ^ std::llround(y / 3) * 19349663);
            h = (h ^ (h >> 29)) * 0xBF58476D1CE4E5B9ull;
            const double texture = 0.1 + 0.17 * (2.0 * static_cast<double>((h >> 11) & 0xFFFF) / 0xFFFF - 1);
            const double dt = std::hypot(x - truth_x, y - truth_y), dd = std::hypot(x - truth_x, y - truth_y - kDecoySouth);
            const double ncc = std::max({texture, 0.9 * std::exp(-dt * dt / 200), 0.3 * std::exp(-dd * dd / 200)});
            out[i] = {static_cast<float>(ncc), static_cast<float>(ncc), 0.0f, 100, kScoreValid};
        }
    }
};

// Runs 120 steps flying east at 12 m/s, 5 Hz, the filter started on the decoy with a 20 m prior
// (so the truth is outside it: only the lock monitor can find it). Returns the final error, m.
double decoy_run(bool monitor, std::size_t& lost_events) {
    LandscapeScorer scorer;
    FilterConfig cfg = small_config(3);
    cfg.lock.enabled = monitor;
    ParticleFilter pf(scorer, cfg);
    pf.initialise(scorer.truth_x, scorer.truth_y + LandscapeScorer::kDecoySouth, kHalfPi);
    const std::vector<std::uint8_t> pixels(16 * 16, 128);
    FilterInput in;
    in.frame = GrayView{pixels.data(), 16, 16, 16};
    in.odometry_east_m = 2.4, in.odometry_north_m = 0, in.heading_rad = kHalfPi;
    for (int step = 0; step < 120; ++step) {
        scorer.truth_x += 2.4;
        pf.step(in);
    }
    lost_events = pf.counters().lock_lost_events;
    return std::hypot(pf.estimate().x - scorer.truth_x, pf.estimate().y - scorer.truth_y);
}

TEST(ParticleFilter, NoticesAMediocreWrongLockAndFindsTheClearOne) {
    std::size_t watched_events = 0, blind_events = 0;
    const double watched = decoy_run(true, watched_events), blind = decoy_run(false, blind_events);
    EXPECT_GT(blind, 40.0) << "without the monitor the decoy should hold the filter";
    EXPECT_EQ(blind_events, 0u);
    EXPECT_GE(watched_events, 1u);
    EXPECT_LT(watched, 10.0) << "the widened search should find the true place " << LandscapeScorer::kDecoySouth << " m away";
}

TEST(ParticleFilter, FixedSeedReproducesTheRunExactly) {
    const LocalizationResult a = run(small_config(7), 6), b = run(small_config(7), 6), c = run(small_config(8), 6);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    bool differs = false;
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        EXPECT_EQ(a.rows[i].estimate_x, b.rows[i].estimate_x);
        EXPECT_EQ(a.rows[i].estimate_y, b.rows[i].estimate_y);
        EXPECT_EQ(a.rows[i].estimate_yaw, b.rows[i].estimate_yaw);
        EXPECT_EQ(a.rows[i].particles, b.rows[i].particles);
        differs |= a.rows[i].estimate_x != c.rows[i].estimate_x;
    }
    EXPECT_TRUE(differs) << "another seed should give another run";
}

TEST(ParticleFilter, SamplingMethodsKeepTheirParticleCounts) {
    FilterConfig cfg = small_config();
    cfg.sampling = SamplingMethod::Importance;
    for (const LocalizationRow& row : run(cfg, 2).rows) EXPECT_EQ(row.particles, 300u);
    cfg.sampling = SamplingMethod::Rejection;
    for (const LocalizationRow& row : run(cfg, 2).rows) EXPECT_EQ(row.particles, 300u);
    cfg.sampling = SamplingMethod::Kld;
    const LocalizationResult k = run(cfg, 30);
    std::size_t fewest = cfg.max_particles;
    for (const LocalizationRow& row : k.rows) {
        EXPECT_GE(row.particles, cfg.min_particles);
        EXPECT_LE(row.particles, cfg.max_particles);
        fewest = std::min(fewest, row.particles);
    }
    EXPECT_EQ(k.rows.front().particles, cfg.max_particles);  // spread over a 20 m disc: the bound is high
    EXPECT_LT(fewest, cfg.max_particles / 2);                  // once the cloud is tight, KLD needs fewer
}

// Wraps a simulated flight and spoils chosen steps, as a real flight can.
class SpoiledFlight : public FlightSource {
public:
    explicit SpoiledFlight(FlightSource& inner) : inner_(inner) {}
    bool next(FlightSample& s) override {
        if (!inner_.next(s)) return false;
        const std::size_t step = count_++;
        if (step == 0 || (step >= 5 && step <= 7)) s.odometry_east_m = s.odometry_north_m = NAN;  // odometry lost
        if (step == 9) s.image = {};                                              // frame failed to load
        if (step == 11) std::fill(s.image.pixels.begin(), s.image.pixels.end(), 0);  // flat frame: every score invalid
        return true;
    }
    std::size_t frames_hint() const override { return inner_.frames_hint(); }

private:
    FlightSource& inner_;
    std::size_t count_ = 0;
};

TEST(ParticleFilter, BadInputIsCountedAndSurvived) {
    FilterConfig cfg = small_config();
    cfg.reinit_radius_m = 20;
    SimulatedFlightSource inner(test_world().world, short_flight(10), 10);
    SpoiledFlight src(inner);
    const LocalizationResult r = localize_flight(src, cfg);
    ASSERT_EQ(r.rows.size(), 50u);
    EXPECT_EQ(r.summary.counters.odometry_lost, 4u);
    EXPECT_EQ(r.summary.counters.frames_missing, 1u);
    EXPECT_EQ(r.summary.counters.reinitialisations, 1u);
    EXPECT_TRUE(r.rows[6].odometry_lost);
    EXPECT_TRUE(r.rows[9].frame_missing);
    EXPECT_TRUE(r.rows[11].reinitialised);
    for (const LocalizationRow& row : r.rows) EXPECT_TRUE(std::isfinite(row.estimate_x) && std::isfinite(row.estimate_y));
    EXPECT_LT(r.rows.back().error_m, 15.0) << "the filter should recover after the bad frames";
}

TEST(ParticleFilter, ParticlesLeavingTheMapAreCountedNotFatal) {
    Rig rig;
    FilterConfig cfg = small_config();
    cfg.init_radius_m = 300;
    ParticleFilter pf(rig.scorer, cfg);
    pf.initialise(20, 20, 0);  // in the map's corner: most templates reach past the edge
    SimulatedFlightSource src(test_world().world, short_flight(0.2), 10);
    FlightSample s;
    ASSERT_TRUE(src.next(s));
    FilterInput in;
    in.frame = s.image.view();
    in.map_px_per_camera_px = s.map_px_per_camera_px;
    const StepReport rep = pf.step(in);
    EXPECT_GT(rep.off_map, rep.particles / 2);
    EXPECT_EQ(pf.counters().particles_off_map, rep.off_map);
}

TEST(ParticleFilter, InitialParticlesLieWithinTheInitRadiusAroundTheHeadingPrior) {
    Rig rig;
    for (const double radius_m : {5.0, 50.0}) {
        FilterConfig cfg = small_config();
        cfg.init_radius_m = radius_m;
        cfg.init_heading_sd_deg = 2;
        ParticleFilter pf(rig.scorer, cfg);
        pf.initialise(300, 250, kHalfPi);
        const double r_px = radius_m / cfg.metres_per_pixel;
        double farthest = 0, mean_cos = 0;
        for (const Particle& p : pf.particles()) {
            farthest = std::max(farthest, std::hypot(p.x - 300, p.y - 250));
            mean_cos += std::cos(p.yaw - kHalfPi);
        }
        mean_cos /= pf.particles().size();
        EXPECT_LE(farthest, r_px) << radius_m;
        EXPECT_GT(farthest, 0.9 * r_px) << radius_m << ": the disc should be filled, not a point";
        EXPECT_GT(mean_cos, std::cos(3 * kPi / 180)) << "headings should stay within a few sd of the prior";
    }
    FilterConfig bad = small_config();
    bad.init_heading_sd_deg = -1;
    EXPECT_THROW(ParticleFilter(rig.scorer, bad), Error);
}

TEST(ParticleFilter, RunLocalizationStartsAtTheGivenPositionAndHeading) {
    FilterConfig cfg = small_config();
    cfg.init_radius_m = 10;
    cfg.init_heading_sd_deg = 1;
    SimulatedFlightSource src(test_world().world, short_flight(0.2), 10);
    const LocalizationResult r = localize_flight(src, cfg, 260, 240, 1.0);
    ASSERT_FALSE(r.rows.empty());
    EXPECT_NEAR(r.rows.front().odometry_x, 260, 1e-9);  // odometry is placed at the given start
    EXPECT_NEAR(r.rows.front().odometry_y, 240, 1e-9);
}

TEST(ParticleFilter, RejectsBadConfigurationAndUseBeforeInitialise) {
    Rig rig;
    FilterConfig bad = small_config();
    bad.max_particles = 10;
    bad.min_particles = 20;
    EXPECT_THROW(ParticleFilter(rig.scorer, bad), Error);
    bad = small_config();
    bad.kld_upper_quantile = 1.0;
    EXPECT_THROW(ParticleFilter(rig.scorer, bad), Error);
    ParticleFilter pf(rig.scorer, small_config());
    EXPECT_THROW(pf.step({}), Error);
    EXPECT_THROW(parse_sampling_method("uniform"), Error);
}

}  // namespace
}  // namespace trn::filter
