// Statistics of repeated bandwidth passes; see stream_stats.hpp.
#include "stream_stats.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace trn::bench {

double coefficient_of_variation(std::span<const double> samples) {
    const std::size_t n = samples.size();
    if (n < 2) return 0;
    double mean = 0;
    for (double v : samples) mean += v;
    mean /= double(n);
    if (mean == 0) return 0;
    double ss = 0;
    for (double v : samples) ss += (v - mean) * (v - mean);
    return std::sqrt(ss / double(n - 1)) / std::abs(mean);
}

RateStats summarize_rates(std::span<const double> samples, const StabilityRule& rule) {
    RateStats s;
    s.samples = samples.size();
    if (samples.empty()) return s;
    const std::size_t window = std::max<std::size_t>(rule.window, 1);
    const std::span<const double> last = samples.size() > window ? samples.last(window) : samples;
    std::vector<double> sorted(last.begin(), last.end());
    std::sort(sorted.begin(), sorted.end());
    const std::size_t k = sorted.size();
    s.median = k % 2 ? sorted[k / 2] : 0.5 * (sorted[k / 2 - 1] + sorted[k / 2]);
    s.cv = coefficient_of_variation(last);
    s.stable = last.size() >= window && s.cv <= rule.max_cv;
    return s;
}

bool enough_passes(std::span<const double> samples, const StabilityRule& rule) {
    return samples.size() >= rule.max_passes || summarize_rates(samples, rule).stable;
}

}  // namespace trn::bench
