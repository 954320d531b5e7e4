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
    // Offset 35, spread 25: the largest k with 25 * 2^k <= 32767 is 10.
    EXPECT_EQ(dense.template_offset, 35.0);
    EXPECT_EQ(dense.template_exponent, 10);
    EXPECT_EQ(dense.quantized[0], -25 * 1024);
    EXPECT_EQ(dense.min_valid_samples(), 6u);  // ceil(0.9 * 6)

    ScoreOptions o;
    o.sampling = Sampling::explicit_points({{2, 1}, {0, 0}});
    const ScoringPlan sparse = make_scoring_plan(GrayView{t.data(), 3, 2, 3}, o);
    EXPECT_FALSE(sparse.dense);
    EXPECT_DOUBLE_EQ(sparse.template_mean, 35.0);  // (60 + 10) / 2
    EXPECT_EQ(sparse.quantized[0], 25 * 1024);
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

TEST(ScoringPlan, QuantizesFloatTemplatesAndRejectsHugeValues) {
    // 8-bit templates are exact: offset an integer, exponent >= 7.
    std::vector<std::uint8_t> u8 = {0, 255, 17, 128};
    const ScoringPlan a = make_scoring_plan(GrayView{u8.data(), 2, 2, 2}, {});
    EXPECT_EQ(a.template_offset, 100.0);  // round(100)
    EXPECT_EQ(a.template_exponent, 7);    // spread 155: 155 * 256 > 32767
    for (std::size_t i = 0; i < u8.size(); ++i) EXPECT_EQ(a.quantized[i], (int(u8[i]) - 100) * 128);
    // Float values are rounded to 2^-k: here offset 0, spread 0.75, k = 15.
    std::vector<float> f = {0.0f, 0.5f, -0.75f, 0.3f};
    const ScoringPlan b = make_scoring_plan(FloatView{f.data(), 2, 2, 2}, {});
    EXPECT_EQ(b.template_offset, 0.0);
    EXPECT_EQ(b.template_exponent, 15);
    EXPECT_EQ(b.quantized[2], -24576);
    EXPECT_EQ(b.quantized[3], std::lround(0.3f * 32768.0));
    for (std::int32_t q : b.quantized) EXPECT_LE(std::abs(q), 32767);
    // Large values get a negative exponent and still fit 16 bits.
    f = {-16777216.0f, 16777216.0f, 0.0f, 1.0f};
    const ScoringPlan c = make_scoring_plan(FloatView{f.data(), 2, 2, 2}, {});
    EXPECT_EQ(c.template_exponent, -10);
    for (std::int32_t q : c.quantized) EXPECT_LE(std::abs(q), 32767);
    // Beyond 2^24 the exact CC / SSD sums could overflow: refused, naming the sample.
    f[3] = 16777218.0f;
    try {
        make_scoring_plan(FloatView{f.data(), 2, 2, 2}, {});
        ADD_FAILURE() << "a template value beyond 2^24 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("template sample 3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("2^24"), std::string::npos) << e.what();
    }
}

// Sums of two samples T = {1, 3}, I = {2, 6} grey levels (perfectly correlated), in fixed point.
ScoringPlan two_sample_plan() {
    ScoringPlan plan;
    plan.width = 2, plan.height = 1;
    plan.quantized = {-128, 128};  // (t - 2) * 2^7
    plan.template_offset = 2;
    plan.template_exponent = 7;
    plan.template_mean = 2;
    plan.min_valid_fraction = 1.0;
    return plan;
}

TEST(FinalizeScore, ScoresFromExactIntegerSums) {
    const ScoringPlan plan = two_sample_plan();
    const std::int64_t i0 = 2 * 128, i1 = 6 * 128;  // I in 1/128 grey levels
    const ParticleSums s{2, i0 + i1, i0 * i0 + i1 * i1, i0 * -128 + i1 * 128, 0, 2 * 128 * 128};
    const ParticleScore r = finalize_score(s, plan);
    ASSERT_TRUE(r.valid());
    EXPECT_EQ(r.ncc, 1.0f);
    const double cc = (1 * 2 + 3 * 6) / std::sqrt((1 + 9) * (4 + 36.0));
    EXPECT_EQ(r.cc, static_cast<float>(cc));
    EXPECT_EQ(r.ssd, static_cast<float>(1 - (1 + 9) / std::sqrt(10 * 40.0)));
    ParticleSums few = s;
    few.n = 1;
    EXPECT_EQ(finalize_score(few, plan).flags, kTooFewSamples);
}

// The largest template (2^24 samples) with the largest values: the int64 sums of fixed_point.hpp
// hold them and the 128-bit products give the exact answer where doubles would cancel to noise.
TEST(FinalizeScore, LargestSumsAreExact) {
    ScoringPlan plan = two_sample_plan();
    plan.quantized.assign(std::size_t(1) << 24, 0);
    plan.template_offset = 0;
    const std::int64_t n = std::int64_t(1) << 24, half = n / 2;
    // I alternates 32640 and 32639 (variance 1/4 of (1/128 grey)^2); T alternates +-32767 in step.
    ParticleSums s;
    s.n = n;
    s.sj = half * (32640 + 32639);
    s.sjj = half * (32640LL * 32640 + 32639LL * 32639);
    s.sjt = half * (32640LL * 32767 - 32639LL * 32767);
    s.st = 0;
    s.stt = n * 32767LL * 32767;
    EXPECT_GT(s.sjj, std::int64_t(1) << 53);  // beyond what a double holds exactly
    plan.min_valid_fraction = 0;
    ParticleScore r = finalize_score(s, plan);
    // var(I) = 1/4 (1/128 grey)^2 = 1.5e-5 grey^2 <= kFlatVariance: flat, decided exactly.
    EXPECT_EQ(r.flags, kFlatPatch);
    // 16 grey levels apart instead (variance 64 grey^2), still perfectly correlated with T.
    const std::int64_t hi = 32640, lo = 32640 - 8 * 128 * 2;
    s.sj = half * (hi + lo);
    s.sjj = half * (hi * hi + lo * lo);
    s.sjt = half * (hi * 32767 - lo * 32767);
    r = finalize_score(s, plan);
    ASSERT_TRUE(r.valid());
    EXPECT_EQ(r.ncc, 1.0f);
}

}  // namespace
}  // namespace trn
