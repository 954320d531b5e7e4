#include "trn/energy/integrate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace trn::energy {
namespace {

// Power of an instant-sample trace at t (t0 <= t <= tN), linear between samples.
double interpolate(const PowerTrace& tr, std::size_t i, double t) {  // t in [t[i-1], t[i]]
    const double a = tr.t[i - 1], b = tr.t[i];
    const double f = (t - a) / (b - a);
    return tr.w[i - 1] + f * (tr.w[i] - tr.w[i - 1]);
}

// The most the integral over [x, y] of a power that stays between w[i-1] and w[i] (anywhere,
// stepping at any time) can differ from the linear interpolation's, for [x, y] inside the sample
// interval [a, b]: |dw| x max of the areas above and below the interpolation's rising share,
// A = int (t-a)/h and B = (y-x) - A. A whole interval gives |dw| h / 2 (the old bound, |dw| x the
// covered length, was twice that); a frame edge at the interval's end side gives |dw| L^2/(2h).
double piece_bound(double dw, double a, double b, double x, double y) {
    const double h = b - a;
    if (!(h > 0)) return 0;
    const double A = ((y - a) * (y - a) - (x - a) * (x - a)) / (2 * h), B = (y - x) - A;
    return std::abs(dw) * std::max(A, B);
}

// Both rules over [s, e] of an instant trace; requires t0 <= s <= e <= tN.
void instant_rules(const PowerTrace& tr, double s, double e, double& trap, double& hold, double* abs_diff = nullptr) {
    trap = hold = 0;
    double diff = 0;
    // First sample strictly after s.
    std::size_t i = static_cast<std::size_t>(std::upper_bound(tr.t.begin(), tr.t.end(), s) - tr.t.begin());
    if (i == 0) i = 1;
    if (i >= tr.size()) i = tr.size() - 1;
    double t_prev = s, p_prev = interpolate(tr, i, s), held = tr.w[i - 1];
    while (i < tr.size() && tr.t[i] < e) {
        const double tz = 0.5 * (p_prev + tr.w[i]) * (tr.t[i] - t_prev), hz = held * (tr.t[i] - t_prev);
        trap += tz, hold += hz, diff += piece_bound(tr.w[i] - tr.w[i - 1], tr.t[i - 1], tr.t[i], t_prev, tr.t[i]);
        t_prev = tr.t[i], p_prev = tr.w[i], held = tr.w[i];
        ++i;
    }
    const std::size_t k = std::min(i, tr.size() - 1);
    const double p_end = interpolate(tr, k, e);
    const double tz = 0.5 * (p_prev + p_end) * (e - t_prev), hz = held * (e - t_prev);
    trap += tz, hold += hz, diff += piece_bound(tr.w[k] - tr.w[k - 1], tr.t[k - 1], tr.t[k], t_prev, e);
    if (abs_diff) *abs_diff = diff;
}

// Interval-mean trace: exact piecewise-constant energy over [s, e], and a linear
// reconstruction through the interval midpoints as the alternative.
void mean_rules(const PowerTrace& tr, double t_begin, double s, double e, double& exact, double& alt) {
    exact = 0;
    double lo = t_begin;
    for (std::size_t i = 0; i < tr.size(); ++i) {
        const double hi = tr.t[i];
        const double a = std::max(lo, s), b = std::min(hi, e);
        if (b > a) exact += tr.w[i] * (b - a);
        lo = hi;
        if (lo >= e) break;
    }
    // Alternative: samples placed at interval midpoints, trapezoid, held flat beyond the ends.
    PowerTrace mid;
    double prev = t_begin;
    for (std::size_t i = 0; i < tr.size(); ++i) {
        mid.t.push_back(0.5 * (prev + tr.t[i]));
        mid.w.push_back(tr.w[i]);
        prev = tr.t[i];
    }
    if (mid.size() < 2) {
        alt = exact;
        return;
    }
    mid.t.insert(mid.t.begin(), t_begin);
    mid.w.insert(mid.w.begin(), mid.w.front());
    mid.t.push_back(tr.t.back());
    mid.w.push_back(mid.w.back());
    double hold = 0;
    instant_rules(mid, s, e, alt, hold);
}

// Sample times uncertain by +-d: the curve through the true times equals the one we integrate
// with its time axis moved by at most d (piecewise linearly, knot by knot), so at each instant
// the two differ by at most the curve's variation within +-d of it; integrated over [s, e] that
// is at most 2 d x the total variation of the samples over [s - d, e + d].
// With a measured spread instead (time_sd_s = sigma, errors independent between samples): moving
// sample k by dk changes the trapezoid by dk (w[k-1] - w[k+1]) / 2, so the energy error has SD
// sigma x sqrt(sum ((w[k+1] - w[k-1]) / 2)^2) over the samples that shape [s, e]; the term is 2 SD
// (95 % for a normal error, more for the bounded, flatter sums of a few uniform lags).
double timing_error(const PowerTrace& tr, double s, double e) {
    if (tr.size() < 2) return 0;
    if (tr.time_sd_s > 0) {
        std::size_t k = static_cast<std::size_t>(std::upper_bound(tr.t.begin(), tr.t.end(), s) - tr.t.begin());
        k = k == 0 ? 0 : k - 1;  // the last sample at or before s
        double sum2 = 0;
        for (; k < tr.size(); ++k) {
            const double before = tr.w[k == 0 ? 0 : k - 1], after = tr.w[k + 1 < tr.size() ? k + 1 : k];
            sum2 += 0.25 * (after - before) * (after - before);
            if (tr.t[k] >= e) break;  // the first sample at or after e is the last that matters
        }
        return 2 * tr.time_sd_s * std::sqrt(sum2);
    }
    const double d = tr.time_uncertainty_s;
    if (!(d > 0)) return 0;
    std::size_t k = static_cast<std::size_t>(std::upper_bound(tr.t.begin(), tr.t.end(), s - d) - tr.t.begin());
    k = k == 0 ? 0 : k - 1;
    double variation = 0;
    for (; k + 1 < tr.size() && tr.t[k] < e + d; ++k) variation += std::abs(tr.w[k + 1] - tr.w[k]);
    return 2 * d * variation;
}

}  // namespace

IntervalEnergy integrate_interval(const PowerTrace& tr, double start, double end, Rule rule) {
    IntervalEnergy r;
    if (tr.size() < 2 || !(end >= start) || !std::isfinite(start) || !std::isfinite(end)) return r;
    const bool mean = tr.kind == SampleKind::IntervalMean;
    const double t_begin = mean ? tr.first_interval_start.value_or(tr.t.front()) : tr.t.front();
    r.covered = start >= t_begin && end <= tr.t.back();
    const auto lo = std::lower_bound(tr.t.begin(), tr.t.end(), start);
    const auto hi = std::upper_bound(tr.t.begin(), tr.t.end(), end);
    r.samples = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, hi - lo));
    if (!r.covered) return r;
    double a = 0, b = 0, spread = 0;
    if (mean) {
        mean_rules(tr, t_begin, start, end, a, b);
        r.energy_j = a, r.other_j = b;
    } else {
        instant_rules(tr, start, end, a, b, &spread);
        r.energy_j = rule == Rule::Trapezoid ? a : b;
        r.other_j = rule == Rule::Trapezoid ? b : a;
    }
    // Between two samples the power can be anywhere between them (a step at either end), so
    // each piece adds |w[k+1] - w[k]| x its length; summed without cancellation between edges.
    r.error_j = std::max(spread, std::abs(a - b)) + 0.5 * tr.resolution_w * (end - start) + timing_error(tr, start, end);
    return r;
}

std::size_t RunEnergy::usable() const {
    return static_cast<std::size_t>(std::count_if(frames.begin(), frames.end(), [](const FrameEnergy& f) { return f.flag.empty(); }));
}

RunEnergy integrate_frames(const PowerTrace& tr, const std::vector<TimedInterval>& intervals, const IntegrationOptions& o) {
    validate_trace(tr);
    RunEnergy run;
    std::vector<TimedInterval> idle, busy;
    for (const auto& iv : intervals) (iv.kind == "idle" ? idle : busy).push_back(iv);
    if (idle.empty()) {
        std::sort(busy.begin(), busy.end(), [](const auto& x, const auto& y) { return x.start < y.start; });
        for (std::size_t i = 1; i < busy.size(); ++i) {
            const double gap = busy[i].start - busy[i - 1].end;
            if (gap > 0) idle.push_back({"idle", static_cast<int>(i - 1), busy[i - 1].end + 0.1 * gap, busy[i].start - 0.1 * gap});
        }
    }
    double idle_j = 0, idle_s = 0;
    std::vector<double> idle_means;
    for (const auto& iv : idle) {
        const IntervalEnergy e = integrate_interval(tr, iv.start, iv.end, o.rule);
        if (!e.covered || iv.end <= iv.start) continue;
        idle_j += e.energy_j, idle_s += iv.end - iv.start;
        idle_means.push_back(e.energy_j / (iv.end - iv.start));
    }
    run.idle_segments = idle_means.size();
    if (idle_s > 0) {
        run.idle_w = idle_j / idle_s;
        run.idle_first_w = idle_means.front(), run.idle_last_w = idle_means.back();
        const double change = run.idle_last_w - run.idle_first_w;
        if (std::abs(change) > o.idle_drift_warn * std::abs(run.idle_w) && std::abs(change) > tr.resolution_w) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "idle power drifted from %.4g W (first idle segment) to %.4g W (last): net energies carry that uncertainty",
                          run.idle_first_w, run.idle_last_w);
            run.warnings.push_back(buf);
        }
    } else {
        run.warnings.push_back("no idle segment inside the trace: net energy equals gross energy (baseline 0 W)");
    }
    for (const auto& iv : intervals) {
        if (iv.kind != "frame") continue;
        FrameEnergy f;
        f.id = iv.id, f.start = iv.start, f.end = iv.end;
        const IntervalEnergy e = integrate_interval(tr, iv.start, iv.end, o.rule);
        f.samples = e.samples;
        if (!e.covered) {
            f.flag = "not covered by the trace";
        } else {
            f.gross_j = e.energy_j;
            f.net_j = e.energy_j - run.idle_w * f.duration();
            f.error_j = e.error_j;
            if (e.samples < o.min_samples) f.flag = std::to_string(e.samples) + " sample(s) < " + std::to_string(o.min_samples);
        }
        run.frames.push_back(f);
    }
    const std::size_t flagged = run.frames.size() - run.usable();
    if (flagged) run.warnings.push_back(std::to_string(flagged) + " of " + std::to_string(run.frames.size()) + " frame(s) flagged (kept in the output with the reason)");
    return run;
}

}  // namespace trn::energy
