#include "trn/energy/align.hpp"

#include <algorithm>
#include <cmath>

#include "trn/error.hpp"

namespace trn::energy {
namespace {

// Cumulative energy at the sample times (trapezoid; interval means placed at their midpoints),
// so the energy of any span is two interpolations: cheap enough for thousands of offsets.
struct CumulativeEnergy {
    std::vector<double> t, c;
    // Times relative to the first sample, so offsets stay small numbers with fine resolution.
    explicit CumulativeEnergy(const PowerTrace& tr) {
        std::vector<double> ts = tr.t;
        if (tr.kind == SampleKind::IntervalMean)
            for (std::size_t i = 0; i < ts.size(); ++i) ts[i] = 0.5 * ((i ? tr.t[i - 1] : tr.first_interval_start.value_or(tr.t[0])) + tr.t[i]);
        for (double& x : ts) x -= tr.t.front();
        t = ts;
        c.assign(ts.size(), 0);
        for (std::size_t i = 1; i < ts.size(); ++i) c[i] = c[i - 1] + 0.5 * (tr.w[i] + tr.w[i - 1]) * (ts[i] - ts[i - 1]);
    }
    double at(double x) const {
        auto it = std::upper_bound(t.begin(), t.end(), x);
        if (it == t.begin()) return c.front();
        if (it == t.end()) return c.back();
        const std::size_t i = static_cast<std::size_t>(it - t.begin());
        const double f = (x - t[i - 1]) / (t[i] - t[i - 1]);
        return c[i - 1] + f * (c[i] - c[i - 1]);
    }
    double energy(double a, double b) const { return at(b) - at(a); }
};

struct Span {
    double start, end;
    bool busy;
};

// Busy-minus-idle mean power of `spans` (marker clock) shifted by `offset`.
double contrast(const CumulativeEnergy& ce, const std::vector<Span>& spans, std::size_t from, std::size_t to, double offset) {
    double eb = 0, tb = 0;
    for (std::size_t i = from; i < to; ++i)
        if (spans[i].busy) eb += ce.energy(spans[i].start + offset, spans[i].end + offset), tb += spans[i].end - spans[i].start;
    const double s0 = spans[from].start, e0 = spans[to - 1].end;
    const double ti = (e0 - s0) - tb, ei = ce.energy(s0 + offset, e0 + offset) - eb;
    if (tb <= 0 || ti <= 0) return 0;
    return eb / tb - ei / ti;
}

// Best offset in [lo, hi]: a grid of at most ~20000 points, then grids 10x finer around the best
// until the step is below `finest`.
double search(const CumulativeEnergy& ce, const std::vector<Span>& spans, std::size_t from, std::size_t to, double lo, double hi,
              double step, double finest, double& final_step) {
    step = std::max(step, (hi - lo) / 20000);
    double best = lo, best_c = -1e300;
    for (;;) {
        const long count = static_cast<long>(std::floor((hi - lo) / step + 1e-9));
        for (long i = 0; i <= count; ++i) {
            const double o = lo + i * step;
            const double c = contrast(ce, spans, from, to, o);
            if (c > best_c) best_c = c, best = o;
        }
        final_step = step;
        if (step <= finest) break;
        lo = std::max(lo, best - 2 * step), hi = std::min(hi, best + 2 * step);
        step /= 10;
    }
    return best;
}

double median_dt(const PowerTrace& tr) {
    std::vector<double> d;
    for (std::size_t i = 1; i < tr.size(); ++i) d.push_back(tr.t[i] - tr.t[i - 1]);
    if (d.empty()) return 0;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return d[d.size() / 2];
}

}  // namespace

Alignment align_auto(const PowerTrace& tr, const MarkerFile& markers, const AlignOptions& o) {
    validate_trace(tr);
    std::vector<Span> spans;
    double min_len = 1e300, busy_total = 0;
    for (const auto& r : markers.rows) {
        const double s = (o.realtime ? r.real_start_ns : r.mono_start_ns) * 1e-9, e = (o.realtime ? r.real_end_ns : r.mono_end_ns) * 1e-9;
        spans.push_back({s, e, r.kind != "idle"});
        if (e > s) min_len = std::min(min_len, e - s);
        if (r.kind != "idle") busy_total += e - s;
    }
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.start < b.start; });
    if (spans.empty() || busy_total <= 0) throw Error("align: the marker file has no busy interval (sync or frame) to align on");
    // Search on relative clocks (markers from their first row, trace from its first sample):
    // UNIX-time offsets are ~1e9 s, where a double cannot resolve microsecond steps.
    const double marker_ref = spans.front().start, trace_ref = tr.t.front(), shift = trace_ref - marker_ref;
    for (auto& sp : spans) sp.start -= marker_ref, sp.end -= marker_ref;
    const CumulativeEnergy ce(tr);
    const double span_s = spans.back().end - spans.front().start;
    double lo = ce.t.front() - spans.front().start, hi = ce.t.back() - spans.back().end;
    if (o.search_s > 0) lo = std::max(lo, o.guess_s - shift - o.search_s), hi = std::min(hi, o.guess_s - shift + o.search_s);
    if (hi < lo)
        throw Error("align: the trace (" + std::to_string(ce.t.back() - ce.t.front()) + " s) cannot hold the marker run (" + std::to_string(span_s) +
                    " s) at any offset in the search range");
    const double dt = median_dt(tr);
    const double finest = std::max(dt / 50, 1e-7);
    Alignment out;
    const double global = search(ce, spans, 0, spans.size(), lo, hi, std::max(min_len / 3, finest), finest, out.step_s);

    // Windows: the frame pattern is periodic, so each window searches less than half a frame
    // period around the global offset.
    std::vector<double> starts;
    for (const auto& s : spans)
        if (s.busy) starts.push_back(s.start);
    double period = span_s;
    if (starts.size() > 2) {
        std::vector<double> d;
        for (std::size_t i = 1; i < starts.size(); ++i) d.push_back(starts[i] - starts[i - 1]);
        std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
        period = d[d.size() / 2];
    }
    const int windows = std::clamp(static_cast<int>(starts.size() / 6), 1, std::max(1, o.windows));
    const double half = std::min(0.4 * period, std::max(5 * dt, 0.002 * span_s));
    for (int k = 0; k < windows && windows > 1; ++k) {
        const std::size_t from = spans.size() * k / windows, to = spans.size() * (k + 1) / windows;
        if (to <= from + 1) continue;
        const double wlo = std::max(ce.t.front() - spans[from].start, global - half), whi = std::min(ce.t.back() - spans[to - 1].end, global + half);
        if (whi < wlo) continue;
        double step = 0;
        out.window_offset_s.push_back(search(ce, spans, from, to, wlo, whi, std::max(half / 200, finest), finest, step));
        out.window_time_s.push_back(0.5 * (spans[from].start + spans[to - 1].end));  // relative until the fit is done
    }
    ClockMapping m;
    m.realtime = o.realtime;
    m.ref_s = 0;
    m.offset_s = global;
    const std::size_t n = out.window_offset_s.size();
    if (n >= 2) {
        double mt = 0, mo = 0, stt = 0, sto = 0;
        for (std::size_t i = 0; i < n; ++i) mt += out.window_time_s[i] - m.ref_s, mo += out.window_offset_s[i];
        mt /= n, mo /= n;
        for (std::size_t i = 0; i < n; ++i) {
            const double dtm = out.window_time_s[i] - m.ref_s - mt;
            stt += dtm * dtm, sto += dtm * (out.window_offset_s[i] - mo);
        }
        m.drift = stt > 0 ? sto / stt : 0;
        m.offset_s = mo - m.drift * mt;
        double ss = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double r = out.window_offset_s[i] - (m.offset_s + m.drift * (out.window_time_s[i] - m.ref_s));
            ss += r * r;
        }
        out.residual_s = std::sqrt(ss / n);
    }
    // Contrast with the final mapping: map every span and measure directly.
    std::vector<Span> mapped;
    for (const auto& s : spans) mapped.push_back({m.map(s.start), m.map(s.end), s.busy});
    out.contrast_w = contrast(ce, mapped, 0, mapped.size(), 0);
    // Back to absolute clocks: t_trace = t + (offset + shift) + drift * (t - marker_ref).
    m.ref_s = marker_ref;
    m.offset_s += shift;
    for (auto& x : out.window_offset_s) x += shift;
    for (auto& x : out.window_time_s) x += marker_ref;
    out.mapping = m;
    return out;
}

ShiftSensitivity shift_sensitivity(const PowerTrace& tr, const MarkerFile& markers, const ClockMapping& mapping, const IntegrationOptions& options) {
    ShiftSensitivity s;
    s.dt_s = median_dt(tr);
    const RunEnergy base = integrate_frames(tr, marker_intervals(markers, mapping), options);
    auto change = [&](double shift) {
        ClockMapping m = mapping;
        m.offset_s += shift;
        const RunEnergy moved = integrate_frames(tr, marker_intervals(markers, m), options);
        double diff = 0, total = 0;
        for (std::size_t i = 0; i < base.frames.size() && i < moved.frames.size(); ++i)
            if (base.frames[i].flag.empty() && moved.frames[i].flag.empty())
                diff += std::abs(moved.frames[i].gross_j - base.frames[i].gross_j), total += std::abs(base.frames[i].gross_j);
        return total > 0 ? diff / total : 0.0;
    };
    s.relative_minus = change(-s.dt_s);
    s.relative_plus = change(s.dt_s);
    return s;
}

}  // namespace trn::energy
