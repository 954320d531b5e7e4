#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "trn/error.hpp"
#include "trn/impl/particle_sums.hpp"
#include "trn/scoring_plan.hpp"

namespace trn {
namespace {

TEST(RandomSamplePoints, DeterministicDistinctAndSized) {
    const auto a = random_sample_points(64, 48, 0.1, 7), b = random_sample_points(64, 48, 0.1, 7);
    const auto c = random_sample_points(64, 48, 0.1, 8);
    ASSERT_EQ(a.size(), std::size_t(std::llround(0.1 * 64 * 48)));
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), [](auto p, auto q) { return p.u == q.u && p.v == q.v; }));
    EXPECT_FALSE(std::equal(a.begin(), a.end(), c.begin(), [](auto p, auto q) { return p.u == q.u && p.v == q.v; }));
    std::set<int> seen;
    for (const SamplePoint& p : a) {
        EXPECT_TRUE(p.u >= 0 && p.u < 64 && p.v >= 0 && p.v < 48);
        EXPECT_TRUE(seen.insert(p.v * 64 + p.u).second) << "duplicate sample";
    }
    EXPECT_EQ(random_sample_points(5, 5, 1e-9, 1).size(), 1u);  // never empty
    EXPECT_EQ(random_sample_points(5, 5, 1.0, 1).size(), 25u);
}

TEST(ScoringPlan, CentresTemplateAndHonoursSampling) {
    std::vector<std::uint8_t> t = {10, 20, 30, 40, 50, 60};
    const ScoringPlan dense = make_scoring_plan(GrayView{t.data(), 3, 2, 3}, {});
    EXPECT_TRUE(dense.dense);
    EXPECT_FLOAT_EQ(dense.cx, 1.0f);
    EXPECT_FLOAT_EQ(dense.cy, 0.5f);
    EXPECT_DOUBLE_EQ(dense.template_mean, 35.0);
    ASSERT_EQ(dense.sample_count(), 6u);
    EXPECT_FLOAT_EQ(dense.centered[0], -25.0f);
    EXPECT_EQ(dense.min_valid_samples(), 6u);  // ceil(0.9 * 6)

    ScoreOptions o;
    o.sampling = Sampling::explicit_points({{2, 1}, {0, 0}});
    const ScoringPlan sparse = make_scoring_plan(GrayView{t.data(), 3, 2, 3}, o);
    EXPECT_FALSE(sparse.dense);
    EXPECT_DOUBLE_EQ(sparse.template_mean, 35.0);  // (60 + 10) / 2
    EXPECT_FLOAT_EQ(sparse.centered[0], 25.0f);
}

TEST(ScoringPlan, RejectsBadArguments) {
    std::vector<std::uint8_t> t(16, 1);
    ScoreOptions o;
    o.sampling = Sampling::explicit_points({{4, 0}});
    EXPECT_THROW(make_scoring_plan(GrayView{t.data(), 4, 4, 4}, o), Error);
    o = {};
    o.min_valid_fraction = 1.5;
    EXPECT_THROW(make_scoring_plan(GrayView{t.data(), 4, 4, 4}, o), Error);
    EXPECT_THROW(make_scoring_plan(GrayView{t.data(), 4, 4, 3}, {}), Error);  // stride < width
    std::vector<float> f(4, 1.0f);
    f[2] = std::nanf("");
    EXPECT_THROW(make_scoring_plan(FloatView{f.data(), 2, 2, 2}, {}), Error);
}

TEST(PoseToAffine, FollowsTheConvention) {
    const Affine a = pose_to_affine({10, 20, std::numbers::pi_v<float> / 2, 2});
    // Template offset (1, 0) lands 2 px below the centre: clockwise on screen.
    EXPECT_NEAR(a.tx + a.a * 1 + a.b * 0, 10.0f, 1e-6);
    EXPECT_NEAR(a.ty + a.c * 1 + a.d * 0, 22.0f, 1e-6);
}

TEST(FinalizeScore, RecoversRawSumsFromShiftedOnes) {
    // Two samples: T = {1, 3} (mean 2), I = {2, 6}: perfectly correlated.
    ScoringPlan plan;
    plan.width = 2, plan.height = 1;
    plan.centered = {-1, 1};
    plan.template_mean = 2;
    plan.min_valid_fraction = 1.0;
    const double shift = 5;  // J = I - 5 = {-3, 1}
    const ParticleSums s{2, -2, 10, 4, 0, 2, shift};
    const ParticleScore r = finalize_score(s, plan);
    ASSERT_TRUE(r.valid());
    EXPECT_NEAR(r.ncc, 1.0, 1e-7);
    const double cc = (1 * 2 + 3 * 6) / std::sqrt((1 + 9) * (4 + 36.0));
    EXPECT_NEAR(r.cc, cc, 1e-7);
    EXPECT_NEAR(r.ssd, 1 - (1 + 9) / std::sqrt(10 * 40.0), 1e-7);
    ParticleSums few = s;
    few.n = 1;
    EXPECT_EQ(finalize_score(few, plan).flags, kTooFewSamples);
}

}  // namespace
}  // namespace trn
