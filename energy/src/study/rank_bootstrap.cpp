// Tests that do not assume normal data: the Wilcoxon/Mann-Whitney rank-sum test (as R's
// wilcox.test), a percentile bootstrap of the ratio of means, Shapiro-Wilk beyond n = 5000 on a
// subsample, and p-values printed as bounds when they underflow.
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>

#include "trn/energy/stats.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

// Counts of the rank-sum statistic U for sample sizes m, n with no ties: the coefficients of the
// Gaussian binomial [m+n choose m]_q = prod_{i=1..m} (1 - q^(n+i)) / (1 - q^i). Doubles: the
// largest count, C(98, 49) ~ 2.5e28, is far inside the range and only ratios are used.
std::vector<double> rank_sum_counts(std::size_t m, std::size_t n) {
    std::vector<double> c(m * n + 1, 0.0);
    c[0] = 1;
    for (std::size_t i = 1; i <= m; ++i) {
        for (std::size_t k = c.size() - 1; k >= n + i; --k) c[k] -= c[k - n - i];  // x (1 - q^(n+i))
        for (std::size_t k = i; k < c.size(); ++k) c[k] += c[k - i];                // / (1 - q^i)
    }
    return c;
}

// Draws an index below n without the modulo bias (so the same seed gives the same draws on any
// standard library: std::uniform_int_distribution is not specified bit for bit).
std::size_t draw(std::mt19937_64& rng, std::size_t n) {
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
    std::uint64_t v;
    do v = rng();
    while (v >= limit);
    return static_cast<std::size_t>(v % n);
}

double mean_of(std::span<const double> x) { return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size()); }

}  // namespace

RankTest mann_whitney_u(std::span<const double> a, std::span<const double> b) {
    if (a.empty() || b.empty()) throw Error("mann_whitney_u: each sample needs at least 1 value");
    const std::size_t na = a.size(), nb = b.size(), n = na + nb;
    std::vector<std::pair<double, int>> all;
    for (double v : a) all.push_back({v, 0});
    for (double v : b) all.push_back({v, 1});
    std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    double rank_sum_a = 0, tie_term = 0;
    bool ties = false;
    for (std::size_t i = 0; i < n;) {
        std::size_t j = i;
        while (j < n && all[j].first == all[i].first) ++j;
        const double mid = 0.5 * static_cast<double>(i + 1 + j);  // average rank of the run i..j-1 (1-based)
        const double t = static_cast<double>(j - i);
        if (t > 1) ties = true, tie_term += t * t * t - t;
        for (std::size_t k = i; k < j; ++k)
            if (all[k].second == 0) rank_sum_a += mid;
        i = j;
    }
    RankTest r;
    const double dna = static_cast<double>(na), dnb = static_cast<double>(nb);
    r.w = rank_sum_a - dna * (dna + 1) / 2;
    r.prob_superiority = r.w / (dna * dnb);
    if (na < 50 && nb < 50 && !ties) {
        r.exact = true;
        const auto c = rank_sum_counts(na, nb);
        const double total = std::accumulate(c.begin(), c.end(), 0.0);
        const auto u = static_cast<std::size_t>(r.w);
        double p;
        if (r.w > dna * dnb / 2) p = std::accumulate(c.begin() + static_cast<std::ptrdiff_t>(u), c.end(), 0.0) / total;  // P(U >= w)
        else p = std::accumulate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(u) + 1, 0.0) / total;            // P(U <= w)
        r.p = std::min(1.0, 2 * p);
        return r;
    }
    const double z0 = r.w - dna * dnb / 2;
    const double sigma = std::sqrt((dna * dnb / 12) * ((static_cast<double>(n) + 1) - tie_term / (static_cast<double>(n) * (static_cast<double>(n) - 1))));
    if (!(sigma > 0)) return r;  // every value equal: no evidence either way (R gives NaN)
    const double z = (z0 - (z0 > 0 ? 0.5 : z0 < 0 ? -0.5 : 0.0)) / sigma;
    const boost::math::normal norm;
    r.p = std::min(1.0, 2 * std::min(boost::math::cdf(norm, z), boost::math::cdf(boost::math::complement(norm, z))));
    return r;
}

BootstrapRatio bootstrap_ratio(std::span<const double> a, std::span<const double> b, std::size_t resamples, unsigned long long seed) {
    if (a.empty() || b.empty()) throw Error("bootstrap_ratio: each sample needs at least 1 value");
    if (resamples < 100) throw Error("bootstrap_ratio: at least 100 resamples");
    BootstrapRatio r;
    const double mb = mean_of(b);
    if (mb == 0) throw Error("bootstrap_ratio: the denominator's mean is 0");
    r.ratio = mean_of(a) / mb;
    std::mt19937_64 rng(seed);
    std::vector<double> ratios;
    ratios.reserve(resamples);
    for (std::size_t k = 0; k < resamples; ++k) {
        double sa = 0, sb = 0;
        for (std::size_t i = 0; i < a.size(); ++i) sa += a[draw(rng, a.size())];
        for (std::size_t i = 0; i < b.size(); ++i) sb += b[draw(rng, b.size())];
        if (sb == 0) {
            ++r.skipped;
            continue;
        }
        ratios.push_back((sa / static_cast<double>(a.size())) / (sb / static_cast<double>(b.size())));
    }
    r.resamples = ratios.size();
    if (ratios.empty()) throw Error("bootstrap_ratio: every resample had a denominator mean of 0");
    r.ci_low = quantile(ratios, 0.025), r.ci_high = quantile(ratios, 0.975);
    return r;
}

Normality normality_test(std::span<const double> x, unsigned long long seed) {
    Normality r;
    r.n = r.used = x.size();
    if (x.size() <= 5000) {
        r.sw = shapiro_wilk(x);
        return r;
    }
    // Partial Fisher-Yates: the first 5000 of a random permutation.
    std::vector<double> v(x.begin(), x.end());
    std::mt19937_64 rng(seed);
    for (std::size_t i = 0; i < 5000; ++i) std::swap(v[i], v[i + draw(rng, v.size() - i)]);
    v.resize(5000);
    r.used = v.size();
    r.sw = shapiro_wilk(v);
    return r;
}

std::string format_p(double p) {
    char buf[32];
    if (std::isnan(p)) return "n/a";
    if (!(p >= kSmallestReportedP)) return "< 1e-300";
    std::snprintf(buf, sizeof buf, p < 1e-4 ? "%.2e" : "%.4f", p);
    return buf;
}

}  // namespace trn::energy
