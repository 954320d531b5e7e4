#pragma once
// When is a bandwidth measurement a limit one can rely on? STREAM passes are repeated until the
// last few agree (coefficient of variation within a bound) or a pass budget runs out; a limit
// whose passes never agreed is reported as unreliable instead of as a ceiling for "% of STREAM".
#include <cstddef>
#include <span>

namespace trn::bench {

struct StabilityRule {
    std::size_t window = 5;        // the last `window` passes must agree ...
    double max_cv = 0.05;          // ... to within this coefficient of variation
    std::size_t max_passes = 20;   // give up (unreliable) after this many passes (20 x 0.3 s on the loaded dev VM)
};

struct RateStats {
    double median = 0;       // of the last `window` samples (all when fewer)
    double cv = 0;           // sample standard deviation / mean of those samples; 0 for fewer than 2
    std::size_t samples = 0;  // samples taken in all
    bool stable = false;     // the window was full and its cv <= max_cv
};

// Sample standard deviation over the mean; 0 for fewer than two samples or a zero mean.
double coefficient_of_variation(std::span<const double> samples);

// The statistics of the last window of `samples` under `rule`.
RateStats summarize_rates(std::span<const double> samples, const StabilityRule& rule);

// True when no more passes are needed: stable, or the pass budget is spent.
bool enough_passes(std::span<const double> samples, const StabilityRule& rule);

}  // namespace trn::bench
