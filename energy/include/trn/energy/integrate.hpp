#pragma once
// Energy of intervals of a power trace. Trapezoid rule with the power interpolated at each
// interval's exact start and end (default), or zero-order hold (each sample held until the
// next). Each frame gets its sample count and an error bound
//     sum over sample intervals of |w[k+1] - w[k]| x max(A, B) + resolution/2 x duration
// where, for the part [x, y] of a sample interval [a, b] inside the frame, A = int_x^y (t-a)/(b-a)
// dt and B = (y - x) - A (true power anywhere between two samples, even a step at either end,
// stays within that: |dw| (b-a)/2 for a whole interval; quantisation adds at most half an LSB at
// every instant), plus a timing term: with a measured spread of the sample times
// (PowerTrace::time_sd_s = sigma) 2 sigma sqrt(sum ((w[k+1] - w[k-1])/2)^2) over the samples
// shaping the frame (95 %); else, when the times are uncertain by +-d
// (PowerTrace::time_uncertainty_s), 2 d x the samples' total variation over [start - d, end + d]
// (worst case). Frames that cannot be measured are flagged, never dropped, and their energy is 0
// rather than NaN.
#include <string>
#include <vector>

#include "trn/energy/markers.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

enum class Rule { Trapezoid, Hold };

struct IntervalEnergy {
    double energy_j = 0;    // by the chosen rule
    double other_j = 0;     // by the other rule
    double error_j = 0;     // bound, see above
    std::size_t samples = 0;  // samples with start <= t <= end
    bool covered = false;   // the trace spans the whole interval
};

IntervalEnergy integrate_interval(const PowerTrace& trace, double start, double end, Rule rule = Rule::Trapezoid);

struct FrameEnergy {
    int id = 0;
    double start = 0, end = 0;
    double gross_j = 0, net_j = 0, error_j = 0;
    std::size_t samples = 0;
    std::string flag;  // "" when usable; else why not ("not covered by the trace", "2 samples < 3")
    double duration() const { return end - start; }
};

struct IntegrationOptions {
    Rule rule = Rule::Trapezoid;
    std::size_t min_samples = 3;     // fewer samples inside a frame -> flagged
    double idle_drift_warn = 0.05;   // relative change of idle power, first vs last idle segment
};

struct RunEnergy {
    std::vector<FrameEnergy> frames;
    double idle_w = 0;               // baseline from idle segments (0 when none could be measured)
    std::size_t idle_segments = 0;
    double idle_first_w = 0, idle_last_w = 0;
    std::vector<std::string> warnings;
    std::size_t usable() const;
};

// Integrates every "frame" interval and derives the idle baseline from "idle" intervals (or,
// when there are none, from the gaps between consecutive busy intervals, trimmed by 10 % at each
// end so tails of the previous frame do not count as idle).
RunEnergy integrate_frames(const PowerTrace& trace, const std::vector<TimedInterval>& intervals, const IntegrationOptions& options = {});

}  // namespace trn::energy
TRN_API_END
