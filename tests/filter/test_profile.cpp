// --profile dissertation (issue 27): the preset's values follow the text (or the stated reading),
// the initial set and the KLD quantile are the ones the filter uses, and eqs. 2.7-2.11 as printed
// move a particle as the equations say (its own heading, the heading change, sample_normal's 1/3).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"
#include "trn/filter/kld.hpp"
#include "trn/filter/motion_model.hpp"
#include "trn/filter/particle_filter.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"

namespace trn::filter {
namespace {

const std::array<double, 5> kNoNoise{0, 0, 0, 0, 0};

TEST(DissertationProfile, ValuesFollowTheText) {
    const FilterConfig c = dissertation_profile();
    EXPECT_NO_THROW(c.validate());
    EXPECT_EQ(c.sampling, SamplingMethod::Kld);
    EXPECT_EQ(c.conversion.to_string(), "logistic:0.2");
    EXPECT_DOUBLE_EQ(c.kld_epsilon, 0.05);
    EXPECT_NEAR(normal_quantile(c.kld_upper_quantile), -1.2815515655446004, 1e-9);  // z_(1-delta), delta = 0.9
    EXPECT_DOUBLE_EQ(c.kld_bin_m, 5);
    EXPECT_EQ(c.initial_particles, 500u);
    EXPECT_EQ(c.fixed_particles, 500u);
    EXPECT_EQ(c.min_particles, 100u);
    EXPECT_EQ(c.max_particles, kDissertationMaxParticles);
    EXPECT_DOUBLE_EQ(c.init_radius_m, 300);
    EXPECT_FALSE(c.lock.enabled);
    EXPECT_EQ(c.motion.equations, MotionEquations::Dissertation);
    EXPECT_FALSE(c.motion.along_heading);
    EXPECT_DOUBLE_EQ(c.motion.alpha1, 1);
    EXPECT_DOUBLE_EQ(c.motion.alpha2, 1);
    EXPECT_DOUBLE_EQ(c.motion.alpha3, 1);
    EXPECT_DOUBLE_EQ(c.init_heading_sd_deg, c.motion.eps_rot_deg / 3);
    // The literal z keeps fewer particles for the same spread than ours (+1.28).
    EXPECT_LT(kld_bound(16, c.kld_epsilon, c.kld_upper_quantile), 0.6 * kld_bound(16, 0.05, FilterConfig{}.kld_upper_quantile));
    // The localizer's preset carries the same filter.
    const localize::LocalizerConfig lc = localize::dissertation_profile();
    EXPECT_EQ(lc.filter.initial_particles, 500u);
    EXPECT_EQ(lc.filter.motion.equations, MotionEquations::Dissertation);
}

TEST(DissertationProfile, OursIsTheDefaultConfig) {
    const FilterConfig o = profile_config(Profile::Ours), d = FilterConfig{};
    EXPECT_DOUBLE_EQ(o.kld_upper_quantile, d.kld_upper_quantile);
    EXPECT_EQ(o.max_particles, d.max_particles);
    EXPECT_EQ(o.initial_particles, 0u);
    EXPECT_TRUE(o.lock.enabled);
    EXPECT_EQ(o.motion.equations, MotionEquations::Ours);
    EXPECT_NEAR(normal_quantile(o.kld_upper_quantile), 1.2815515655446004, 1e-9);
}

TEST(DissertationProfile, NamesParse) {
    EXPECT_EQ(parse_profile("ours"), Profile::Ours);
    EXPECT_EQ(parse_profile("dissertation"), Profile::Dissertation);
    EXPECT_STREQ(to_string(Profile::Dissertation), "dissertation");
    try {
        parse_profile("literal");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ours or dissertation"), std::string::npos) << e.what();
    }
}

class NoScorer : public ParticleScorer {
public:
    void score(GrayView, double, std::span<const Pose>, std::span<ParticleScore>, PhaseTimes*) override { FAIL() << "not scored"; }
};

TEST(DissertationProfile, InitialSetIsTheTextsFiveHundred) {
    NoScorer scorer;
    FilterConfig d = dissertation_profile();
    ParticleFilter filter(scorer, d);
    filter.initialise(1000, 1000, 0.5);
    EXPECT_EQ(filter.particles().size(), 500u);
    ParticleFilter ours(scorer, FilterConfig{});
    ours.initialise(1000, 1000, 0.5);
    EXPECT_EQ(ours.particles().size(), FilterConfig{}.max_particles);  // ours: the initial set is the maximum
    FilterConfig fixed;
    fixed.sampling = SamplingMethod::Importance;
    ParticleFilter importance(scorer, fixed);
    importance.initialise(1000, 1000, 0.5);
    EXPECT_EQ(importance.particles().size(), fixed.fixed_particles);
    // Headings: one magnetometer reading around the start heading (sd eps_rot / 3 = 2 deg).
    double s2 = 0;
    for (const Particle& p : filter.particles()) s2 += std::pow(std::remainder(p.yaw - 0.5, 2 * kPi), 2);
    EXPECT_NEAR(std::sqrt(s2 / 500) / kDeg, 2.0, 0.3);
}

// A track that turns (no crab: the heading is the course), each step's measured heading given.
TEST(DissertationMotion, NoiseFreeParticleFollowsATurningTrackByTheHeadingChanges) {
    MotionModel model = dissertation_profile().motion;
    const double mpp = 0.5;
    double x = 100, y = 200, yaw = 90 * kDeg, tx = x, ty = y, last = yaw;
    for (int i = 0; i < 100; ++i) {
        const double course = (90 + 0.8 * i) * kDeg, d = 2.4;
        const double east = d * std::sin(course), north = d * std::cos(course);
        const StepMotion m = make_step_motion(east, north, course, course, wrap_angle(course - last), mpp);
        last = course;
        propagate_particle(model, m, mpp, kNoNoise, x, y, yaw);
        tx += east / mpp, ty -= north / mpp;
        EXPECT_NEAR(yaw, wrap_angle(course), 1e-9);
    }
    EXPECT_LT(std::hypot(x - tx, y - ty) * mpp, 1e-6);
}

TEST(DissertationMotion, KeepsItsOwnHeadingAndAddsSampleNormalWithSdOneThird) {
    const MotionModel model = dissertation_profile().motion;  // eps_tran 3 m, eps_rot 6 deg
    const double mpp = 1;
    // Heading change +10 deg this step; the particle's own yaw is 20 deg off the measured heading and stays so.
    const StepMotion m = make_step_motion(0, 10, 10 * kDeg, 10 * kDeg, 10 * kDeg, mpp);
    double x = 0, y = 0, yaw = 20 * kDeg;
    propagate_particle(model, m, mpp, kNoNoise, x, y, yaw);
    EXPECT_NEAR(yaw / kDeg, 30, 1e-9);  // theta + delta_rot: not reset to the magnetometer's 10
    EXPECT_NEAR(std::hypot(x, y), 10, 1e-9);
    EXPECT_NEAR(std::atan2(x, -y) / kDeg, 30, 1e-9);  // moved along its own heading
    // One sd of each draw: eps / 3.
    x = y = 0, yaw = 20 * kDeg;
    propagate_particle(model, m, mpp, {1, 1, 0, 0, 0}, x, y, yaw);
    EXPECT_NEAR(yaw / kDeg, 30 + 6.0 / 3, 1e-9);
    EXPECT_NEAR(std::hypot(x, y), 10 + 3.0 / 3, 1e-9);
    // The alphas scale the motion: eqs. 2.7 / 2.8 / 2.9.
    MotionModel half = model;
    half.alpha1 = half.alpha2 = 0.5, half.alpha3 = 0.5;
    x = y = 0, yaw = 20 * kDeg;
    propagate_particle(half, m, mpp, kNoNoise, x, y, yaw);
    EXPECT_NEAR(yaw / kDeg, 25, 1e-9);
    EXPECT_NEAR(std::hypot(x, y), 5, 1e-9);
}

TEST(DissertationMotion, AlongHeadingIsAnOptionOfOursOnly) {
    MotionModel m = dissertation_profile().motion;
    m.along_heading = true;
    EXPECT_THROW(m.validate(), Error);
}

}  // namespace
}  // namespace trn::filter
