#pragma once
// Statistics for energy comparisons: summaries with 95 % CIs, the Shapiro-Wilk test (Royston
// 1995, AS R94, as in R's shapiro.test; n = 3..5000), Welch / Student t-tests, Holm correction
// and ratios of means with CIs. Distributions come from Boost.Math.
#include <cstddef>
#include <span>
#include <string>
#include <vector>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct Summary {
    std::size_t n = 0;
    double mean = 0, sd = 0, median = 0, q1 = 0, q3 = 0;
    double ci_low = 0, ci_high = 0;  // 95 % CI of the mean (t distribution); = mean when n < 2
    double iqr() const { return q3 - q1; }
};
Summary summarize(std::span<const double> x);
// Quantile by linear interpolation between order statistics (R's type 7).
double quantile(std::vector<double> x, double p);

struct ShapiroWilk {
    double w = 0, p = 0;
};
// Throws trn::Error for n outside 3..5000 or all-equal data.
ShapiroWilk shapiro_wilk(std::span<const double> x);

struct TTest {
    double t = 0, df = 0, p = 0;              // two-sided
    double diff = 0, ci_low = 0, ci_high = 0;  // mean(a) - mean(b) with 95 % CI
};
TTest welch_t_test(std::span<const double> a, std::span<const double> b);
TTest student_t_test(std::span<const double> a, std::span<const double> b);

// Holm-adjusted p-values, in the input order (as R's p.adjust(p, "holm")).
std::vector<double> holm_adjust(std::span<const double> p);

struct Ratio {
    double ratio = 0, ci_low = 0, ci_high = 0;  // mean(a)/mean(b); 95 % CI by the delta method on log ratio
};
Ratio ratio_of_means(std::span<const double> a, std::span<const double> b);

// Wilcoxon rank-sum / Mann-Whitney U test, two-sided, as R's wilcox.test(a, b): W = rank sum of
// a minus n_a(n_a+1)/2; exact distribution when both n < 50 and there are no ties, else the
// normal approximation with tie and continuity correction. Needs at least one value in each.
struct RankTest {
    double w = 0, p = 1;
    bool exact = false;
    // P(a > b) + P(a = b)/2 estimated as W/(n_a n_b): 0.5 when neither tends to be larger.
    double prob_superiority = 0.5;
};
RankTest mann_whitney_u(std::span<const double> a, std::span<const double> b);

// Percentile bootstrap 95 % CI of mean(a)/mean(b): each sample resampled with replacement on its
// own, `resamples` times, from a fixed seed (the same data give the same interval).
struct BootstrapRatio {
    double ratio = 0, ci_low = 0, ci_high = 0;
    std::size_t resamples = 0, skipped = 0;  // skipped: resamples whose denominator mean was 0
};
BootstrapRatio bootstrap_ratio(std::span<const double> a, std::span<const double> b, std::size_t resamples = 10000, unsigned long long seed = 1);

// Shapiro-Wilk for any n >= 3: above 5000 (the limit of Royston's approximation, as R refuses) on
// a random subsample of 5000 drawn without replacement from a fixed seed; `subsample` says so.
struct Normality {
    ShapiroWilk sw;
    std::size_t n = 0, used = 0;  // values given / values tested
    bool subsampled() const { return used < n; }
};
Normality normality_test(std::span<const double> x, unsigned long long seed = 1);

// A p-value as text: "0.0123", "3.45e-07", and below the smallest meaningful double a bound
// "< 1e-300" instead of 0.00e+00 (a t or normal tail that underflowed).
inline constexpr double kSmallestReportedP = 1e-300;
std::string format_p(double p);

}  // namespace trn::energy
TRN_API_END
