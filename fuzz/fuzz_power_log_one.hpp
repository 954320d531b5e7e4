#pragma once
// One fuzz input through a parser and everything downstream of it: a parse may refuse the input
// with trn::Error, but it must never crash, and what it accepts must integrate to finite joules.
// fuzz_power_log.cpp's check, built as a libFuzzer target and as a ctest replay by
// fuzz/CMakeLists.txt (the marker file has its own entry, fuzz_markers.cpp).
#include <cmath>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/time_zone.hpp"
#include "trn/error.hpp"

namespace trn::energy::fuzz {

using trn::fuzz::violation;

// Returns true when the parser accepted the input.
inline bool run_one(const std::string& format, std::string_view input) {
    PowerTrace tr;
    try {
        tr = parse_power_log(input, "fuzz", format);
    } catch (const trn::Error&) {
        return false;  // a clear refusal is the right answer to garbage
    }
    for (std::size_t i = 0; i < tr.size(); ++i) {
        if (!std::isfinite(tr.t[i]) || !std::isfinite(tr.w[i])) violation("non-finite sample accepted");
        if (i && !(tr.t[i] > tr.t[i - 1])) violation("times not strictly increasing");
    }
    if (tr.size() < 2) return true;
    const double a = tr.first_interval_start.value_or(tr.t.front()), b = tr.t.back();
    const IntervalEnergy e = integrate_interval(tr, a, b);
    if (!std::isfinite(e.energy_j) || !std::isfinite(e.error_j)) violation("NaN/inf joules for the whole trace");
    const IntervalEnergy half = integrate_interval(tr, a + 0.25 * (b - a), a + 0.75 * (b - a), Rule::Hold);
    if (!std::isfinite(half.energy_j) || !std::isfinite(half.error_j)) violation("NaN/inf joules for a span");
    std::vector<TimedInterval> frames;
    try {
        frames = intervals_from_trace_markers(tr);
    } catch (const trn::Error&) {
    }
    if (frames.empty()) frames = {{"frame", 0, a, 0.5 * (a + b)}, {"frame", 1, 0.5 * (a + b) + 1e-9 * (b - a), b}};
    const RunEnergy run = integrate_frames(tr, frames);
    if (!std::isfinite(run.idle_w)) violation("NaN idle power");
    for (const auto& f : run.frames)
        if (!std::isfinite(f.gross_j) || !std::isfinite(f.net_j) || !std::isfinite(f.error_j)) violation("NaN/inf frame joules");
    // Local wall-clock stamps moved to UTC must stay finite and increasing (or be refused).
    if (tr.local_time) {
        try {
            apply_time_zone(tr, TimeZone::fixed("+05:30"));
            for (std::size_t i = 1; i < tr.size(); ++i)
                if (!(tr.t[i] > tr.t[i - 1]) || !std::isfinite(tr.t[i])) violation("time zone broke the order of samples");
        } catch (const trn::Error&) {
        }
    }
    return true;
}

}  // namespace trn::energy::fuzz
