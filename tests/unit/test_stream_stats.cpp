// The statistics behind the STREAM limit (bench/stream_stats.*): when passes count as agreeing,
// and that a limit whose passes keep varying is marked unreliable rather than reported as stable.
#include <gtest/gtest.h>

#include <vector>

#include "../../bench/stream_stats.hpp"

namespace trn::bench {
namespace {

TEST(StreamStats, CoefficientOfVariationIsSampleStdOverMean) {
    EXPECT_DOUBLE_EQ(coefficient_of_variation(std::vector<double>{1, 2, 3}), 0.5);  // sd 1, mean 2
    EXPECT_DOUBLE_EQ(coefficient_of_variation(std::vector<double>{7}), 0.0);
    EXPECT_DOUBLE_EQ(coefficient_of_variation(std::vector<double>{}), 0.0);
    EXPECT_NEAR(coefficient_of_variation(std::vector<double>{19, 70}), 36.06 / 44.5, 1e-3);
}

TEST(StreamStats, AgreeingPassesAreStableAndReportTheirMedian) {
    const StabilityRule rule;  // 5 passes within 5 %
    const std::vector<double> rates = {20.0, 20.4, 19.8, 20.1, 20.2};
    const RateStats s = summarize_rates(rates, rule);
    EXPECT_TRUE(s.stable);
    EXPECT_DOUBLE_EQ(s.median, 20.1);
    EXPECT_LT(s.cv, 0.05);
    EXPECT_TRUE(enough_passes(rates, rule));
}

TEST(StreamStats, TooFewPassesAreNotYetStable) {
    const StabilityRule rule;
    const std::vector<double> rates = {20.0, 20.0, 20.0, 20.0};
    EXPECT_FALSE(summarize_rates(rates, rule).stable);
    EXPECT_FALSE(enough_passes(rates, rule));
}

TEST(StreamStats, OnlyTheLastWindowCounts) {
    const StabilityRule rule;
    const std::vector<double> rates = {5.0, 70.0, 19.0, 20.0, 20.5, 19.9, 20.2, 20.1};  // warm-up noise, then agreement
    const RateStats s = summarize_rates(rates, rule);
    EXPECT_TRUE(s.stable);
    EXPECT_EQ(s.samples, 8u);
    EXPECT_DOUBLE_EQ(s.median, 20.1);
}

// The case of issue 14: copy passes between 19 and 70 GB/s never agree; after the pass budget the
// limit stops repeating and is marked unreliable (not stable), with its variation reported.
TEST(StreamStats, PersistentVariationEndsUnreliable) {
    StabilityRule rule;
    rule.max_passes = 12;
    std::vector<double> rates;
    while (!enough_passes(rates, rule)) rates.push_back(rates.size() % 2 ? 70.0 : 19.0);
    EXPECT_EQ(rates.size(), 12u);
    const RateStats s = summarize_rates(rates, rule);
    EXPECT_FALSE(s.stable);
    EXPECT_GT(s.cv, rule.max_cv);
}

TEST(StreamStats, ThresholdIsInclusiveAndConfigurable) {
    StabilityRule rule;
    rule.window = 3;
    rule.max_cv = 0.5;
    EXPECT_TRUE(summarize_rates(std::vector<double>{1, 2, 3}, rule).stable);  // cv exactly 0.5
    rule.max_cv = 0.49;
    EXPECT_FALSE(summarize_rates(std::vector<double>{1, 2, 3}, rule).stable);
}

}  // namespace
}  // namespace trn::bench
