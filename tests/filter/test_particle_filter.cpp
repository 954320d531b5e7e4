// The particle filter on a real backend and simulated flights: it must track, reproduce a seeded
// run exactly, keep the sampling counts its method promises and survive bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "filter_test_world.hpp"
#include "trn/error.hpp"
#include "trn/filter/localization.hpp"
#include "trn/filter/particle_filter.hpp"

namespace trn::filter {
namespace {

using testing::short_flight;
using testing::test_world;

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

LocalizationResult run(const FilterConfig& cfg, double seconds, std::uint64_t flight_seed = 5) {
    Rig rig;
    ParticleFilter pf(rig.scorer, cfg);
    SimulatedFlightSource src(test_world().world, short_flight(seconds, flight_seed), 10);
    return run_localization(src, pf);
}

TEST(ParticleFilter, TracksTheAircraftBetterThanOdometry) {
    const LocalizationResult r = run(small_config(), 30);
    ASSERT_EQ(r.rows.size(), 150u);
    EXPECT_LT(r.rows.back().error_m, 10.0);
    EXPECT_LT(r.summary.filter_final_error_m, 0.5 * r.summary.odometry_final_error_m);
    EXPECT_LT(r.summary.filter_mean_error_m, r.summary.odometry_mean_error_m);
    EXPECT_EQ(r.summary.counters.reinitialisations, 0u);
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
    Rig rig;
    FilterConfig cfg = small_config();
    cfg.reinit_radius_m = 20;
    ParticleFilter pf(rig.scorer, cfg);
    SimulatedFlightSource inner(test_world().world, short_flight(10), 10);
    SpoiledFlight src(inner);
    const LocalizationResult r = run_localization(src, pf);
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
