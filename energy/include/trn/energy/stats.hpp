#pragma once
// Statistics for energy comparisons: summaries with 95 % CIs, the Shapiro-Wilk test (Royston
// 1995, AS R94, as in R's shapiro.test; n = 3..5000), Welch / Student t-tests, Holm correction
// and ratios of means with CIs. Distributions come from Boost.Math.
#include <cstddef>
#include <span>
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

}  // namespace trn::energy
TRN_API_END
