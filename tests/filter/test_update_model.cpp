// The update's rules for what a frame may tell (filter::UpdateModel, issue 42), on a scorer whose
// answers are set by the test: a frame over no-data is no evidence and no collapse; a particle
// without a valid score keeps a poor-but-possible weight; one distinct frame is believed in part.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <functional>

#include "trn/error.hpp"
#include "trn/filter/particle_filter.hpp"

namespace trn::filter {
namespace {

// Scores each pose by a rule of its position; no image is read.
struct RuleScorer : ParticleScorer {
    std::function<ParticleScore(const Pose&)> rule;
    void score(GrayView, double, std::span<const Pose> poses, std::span<ParticleScore> out, PhaseTimes*) override {
        for (std::size_t i = 0; i < poses.size(); ++i) out[i] = rule(poses[i]);
    }
};

ParticleScore valid(float ncc) {
    ParticleScore s;
    s.ncc = ncc, s.valid_samples = 100, s.flags = kScoreValid;
    return s;
}
ParticleScore invalid() {
    ParticleScore s;
    s.flags = kScoreValid + 1;  // any flag but "valid"
    return s;
}

FilterConfig config(bool ours) {
    FilterConfig c = ours ? FilterConfig{} : dissertation_profile();
    c.metres_per_pixel = 1;
    c.lock.enabled = false;
    c.init_radius_m = c.reinit_radius_m = 50;
    c.max_particles = 1000, c.min_particles = 1000, c.initial_particles = 1000;  // a fixed count: the weights are the subject
    return c;
}

FilterInput frame_input() {
    static const std::vector<std::uint8_t> pixels(16 * 16, 128);
    FilterInput in;
    in.frame = GrayView{pixels.data(), 16, 16, 16};
    in.odometry_east_m = in.odometry_north_m = 0;
    in.heading_rad = 0;
    return in;
}

TEST(UpdateModel, AFrameOverNoDataTellsNothingAndCollapsesNothing) {
    RuleScorer scorer;
    scorer.rule = [](const Pose&) { return invalid(); };
    ParticleFilter ours(scorer, config(true));
    ours.initialise(500, 500, 0);
    const StepReport r = ours.step(frame_input());
    EXPECT_FALSE(r.reinitialised);
    EXPECT_EQ(r.frame_weight, 0.0);
    EXPECT_EQ(r.off_map, r.particles);
    for (const Particle& p : ours.particles()) ASSERT_EQ(p.weight, 1.0);
    EXPECT_LT(std::hypot(ours.estimate().x - 500, ours.estimate().y - 500), 5.0) << "the cloud stays where the motion put it";
    // The dissertation's update gives every particle weight 0: a collapse, redrawn within reinit_radius_m.
    ParticleFilter literal(scorer, config(false));
    literal.initialise(500, 500, 0);
    EXPECT_TRUE(literal.step(frame_input()).reinitialised);
}

TEST(UpdateModel, AParticleWithoutAValidScoreGetsTheChosenQuantileOfTheValidOnes) {
    // West of x = 500 the map is no-data; east of it the NCC rises with x from 0 to ~0.5.
    RuleScorer scorer;
    scorer.rule = [](const Pose& p) { return p.x < 500 ? invalid() : valid(static_cast<float>((p.x - 500) / 100)); };
    FilterConfig c = config(true);
    c.update.min_ess_fraction = 0;  // the weights as converted
    c.update.unknown_quantile = 0.25;
    ParticleFilter pf(scorer, c);
    pf.initialise(500, 500, 0);
    const StepReport r = pf.step(frame_input());
    ASSERT_GT(r.off_map, 300u);
    ASSERT_LT(r.off_map, 700u);
    std::vector<double> valid_w;
    double unknown_w = -1;
    for (const Particle& p : pf.particles()) {
        if (static_cast<float>(p.x) < 500.0f) {  // as the scorer saw it
            if (unknown_w < 0) unknown_w = p.weight;
            ASSERT_EQ(p.weight, unknown_w) << "every unknown particle weighs the same";
        } else {
            valid_w.push_back(p.weight);
        }
    }
    std::sort(valid_w.begin(), valid_w.end());
    const double q = valid_w[static_cast<std::size_t>(std::lround(0.25 * (valid_w.size() - 1)))];
    EXPECT_DOUBLE_EQ(unknown_w, q);
    EXPECT_GT(unknown_w, 0.0);
    EXPECT_LT(unknown_w, valid_w.back()) << "a place that matches beats one that cannot be checked";
    // Quantile 0: the worst scored place's weight.
    c.update.unknown_quantile = 0;
    ParticleFilter worst(scorer, c);
    worst.initialise(500, 500, 0);
    worst.step(frame_input());
    double lowest = 2, unknown = -1;
    for (const Particle& p : worst.particles()) {
        if (static_cast<float>(p.x) < 500.0f)
            unknown = p.weight;
        else
            lowest = std::min(lowest, p.weight);
    }
    EXPECT_GT(unknown, 0.0);
    EXPECT_LE(unknown, lowest * (1 + 1e-12));
}

TEST(UpdateModel, ADistinctFrameIsBelievedInPartAndAFlatOneWhole) {
    RuleScorer scorer;
    // One small patch matches (NCC 0.9), everything else scores 0.
    scorer.rule = [](const Pose& p) { return valid(std::hypot(p.x - 520, p.y - 500) < 3 ? 0.9f : 0.0f); };
    FilterConfig c = config(true);
    c.update.min_ess_fraction = 0.3;
    ParticleFilter pf(scorer, c);
    pf.initialise(500, 500, 0);
    const StepReport r = pf.step(frame_input());
    EXPECT_GT(r.frame_weight, 0.0);
    EXPECT_LT(r.frame_weight, 1.0);
    double s = 0, s2 = 0;
    for (const Particle& p : pf.particles()) s += p.weight, s2 += p.weight * p.weight;
    EXPECT_GE(s * s / s2, 0.3 * static_cast<double>(pf.particles().size()) * 0.999);
    // Without tempering the same frame puts nearly all the weight on the patch.
    c.update.min_ess_fraction = 0;
    ParticleFilter whole(scorer, c);
    whole.initialise(500, 500, 0);
    EXPECT_EQ(whole.step(frame_input()).frame_weight, 1.0);
    // A frame whose scores are all alike is taken whole: it cannot collapse the cloud.
    scorer.rule = [](const Pose&) { return valid(0.2f); };
    ParticleFilter flat(scorer, config(true));
    flat.initialise(500, 500, 0);
    EXPECT_EQ(flat.step(frame_input()).frame_weight, 1.0);
}

// Without a compass the odometry's direction is each particle's own guess until the yaw settles:
// from the start the map is the prior (as after lost odometry). A particle off the map weighs 0 and
// one whose patch is partly off it (below 0.9 of a whole patch) too, until the cloud has gathered
// within 10 m; with a compass, or once settled, "unknown is not impossible" as above.
TEST(UpdateModel, ACompasslessStartTakesTheMapAsThePriorUntilTheCloudSettles) {
    // West of x = 490 no-data; 490..510 the patch is partly on the map (60 of 100 samples); east of
    // it whole (100). Every scored place has the same NCC: only the rule decides the weights.
    RuleScorer scorer;
    scorer.rule = [](const Pose& p) {
        if (p.x < 490) return invalid();
        ParticleScore s = valid(0.3f);
        if (p.x < 510) s.valid_samples = 60;
        return s;
    };
    const auto weights = [&](HeadingMode heading, double x, double radius_m) {
        FilterConfig c = config(true);
        c.heading = heading;
        c.init_radius_m = radius_m;
        c.update.min_ess_fraction = 0;
        ParticleFilter pf(scorer, c);
        pf.initialise(x, 500, heading == HeadingMode::None ? NAN : 0.0);
        FilterInput in = frame_input();
        if (heading == HeadingMode::None) in.heading_rad = NAN;
        pf.step(in);
        double off = 0, partial = 0, whole = 0;  // the largest weight of each kind
        for (const Particle& p : pf.particles()) {
            const float x = static_cast<float>(p.x);  // as the scorer saw it
            double& kind = x < 490 ? off : x < 510 ? partial : whole;
            kind = std::max(kind, p.weight);
        }
        return std::array<double, 3>{off, partial, whole};
    };
    const auto start = weights(HeadingMode::None, 500, 50);  // a 50 m circle: spread ~35 m, not settled
    EXPECT_EQ(start[0], 0.0) << "off the map, from a compass-less start";
    EXPECT_EQ(start[1], 0.0) << "60 % of a patch, from a compass-less start";
    EXPECT_GT(start[2], 0.0);
    const auto compass = weights(HeadingMode::Compass, 500, 50);
    EXPECT_GT(compass[0], 0.0) << "with a compass the start circle is a supported position";
    EXPECT_GT(compass[1], 0.0);
    const auto settled = weights(HeadingMode::None, 490, 6);  // a 6 m circle on the edge: spread ~4 m, settled
    EXPECT_GT(settled[0], 0.0);
    EXPECT_GT(settled[1], 0.0);
}

TEST(UpdateModel, RefusesOutOfRangeSettings) {
    FilterConfig c = config(true);
    c.update.min_ess_fraction = 1.5;
    EXPECT_THROW(c.validate(), Error);
    c = config(true);
    c.update.unknown_quantile = -0.1;
    EXPECT_THROW(c.validate(), Error);
    c.update.unknown_quantile = NAN;
    EXPECT_THROW(c.validate(), Error);
    c = config(true);
    c.update.min_valid_fraction = 0;
    EXPECT_THROW(c.validate(), Error);
}

}  // namespace
}  // namespace trn::filter
