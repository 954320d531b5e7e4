#include "trn/energy/align.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trn/error.hpp"

namespace trn::energy {
namespace {

// Cumulative energy at the sample times (trapezoid; interval means placed at their midpoints),
// so the energy of any span is two look-ups: cheap enough for thousands of offsets.
struct CumulativeEnergy {
    std::vector<double> t, w, c;
    // Times relative to the first sample, so offsets stay small numbers with fine resolution.
    explicit CumulativeEnergy(const PowerTrace& tr) {
        std::vector<double> ts = tr.t;
        if (tr.kind == SampleKind::IntervalMean)
            for (std::size_t i = 0; i < ts.size(); ++i) ts[i] = 0.5 * ((i ? tr.t[i - 1] : tr.first_interval_start.value_or(tr.t[0])) + tr.t[i]);
        for (double& x : ts) x -= tr.t.front();
        t = ts;
        w = tr.w;
        c.assign(ts.size(), 0);
        for (std::size_t i = 1; i < ts.size(); ++i) c[i] = c[i - 1] + 0.5 * (tr.w[i] + tr.w[i - 1]) * (ts[i] - ts[i - 1]);
    }
    double at(double x) const {
        auto it = std::upper_bound(t.begin(), t.end(), x);
        if (it == t.begin()) return c.front();
        if (it == t.end()) return c.back();
        const std::size_t i = static_cast<std::size_t>(it - t.begin());
        // Exact integral of the linear interpolant (as the trapezoid rule of integrate_interval):
        // interpolating the cumulative linearly would hold power flat across each sample
        // interval and leave every edge's position flat within its interval, so the search
        // would settle anywhere on that plateau (biased offsets, spurious drift).
        const double h = t[i] - t[i - 1], f = (x - t[i - 1]) / h;
        return c[i - 1] + h * f * (w[i - 1] + 0.5 * f * (w[i] - w[i - 1]));
    }
    double energy(double a, double b) const { return at(b) - at(a); }
};

struct Span {
    double start, end;
    bool busy, sync;
};

// Marker time -> trace time (both relative): t + a + d * (t - tc).
struct Line {
    double a = 0, d = 0, tc = 0;
    double map(double t) const { return t + a + d * (t - tc); }
};

// Busy-minus-idle mean power of `spans` mapped by `m` (watts), and the score the searches
// maximise: the two-level least-squares fit's between-class sum of squares, contrast^2 x
// tb x ti / (tb + ti), signed. For a pure offset the two rank alike; with drift, the plain
// contrast would reward squeezing the busy spans off their edge samples (a spurious negative
// drift), which the weight by busy time cancels. Every span counts only its own mapped interval,
// so a segment's edges are treated alike whichever way the mapping moves.
struct Fit {
    double contrast = 0, score = 0;
};
Fit fit(const CumulativeEnergy& ce, const std::vector<Span>& spans, const Line& m) {
    double eb = 0, tb = 0, ei = 0, ti = 0;
    for (const auto& s : spans) {
        const double a = m.map(s.start), b = m.map(s.end), e = ce.energy(a, b);
        if (s.busy) eb += e, tb += b - a;
        else ei += e, ti += b - a;
    }
    if (tb <= 0 || ti <= 0) return {};
    const double c = eb / tb - ei / ti;
    return {c, c * std::abs(c) * tb * ti / (tb + ti)};
}
double contrast(const CumulativeEnergy& ce, const std::vector<Span>& spans, const Line& m) { return fit(ce, spans, m).contrast; }
double score(const CumulativeEnergy& ce, const std::vector<Span>& spans, const Line& m) { return fit(ce, spans, m).score; }

// Best x in [lo, hi] for `score`: a grid of at most ~20000 points, then grids 10x finer around
// the best until the step is below `finest`. `coarse` receives the first grid.
template <class Score>
double search(const Score& score, double lo, double hi, double step, double finest, double& final_step,
              std::vector<std::pair<double, double>>* coarse = nullptr) {
    step = std::max({step, (hi - lo) / 20000, finest});
    double best = lo, best_c = -1e300;
    for (bool first = true;; first = false) {
        const long count = static_cast<long>(std::floor((hi - lo) / step + 1e-9));
        for (long i = 0; i <= count; ++i) {
            const double x = lo + i * step;
            const double c = score(x);
            if (first && coarse) coarse->push_back({x, c});
            if (c > best_c) best_c = c, best = x;
        }
        final_step = step;
        if (step <= finest) break;
        lo = std::max(lo, best - 2 * step), hi = std::min(hi, best + 2 * step);
        step /= 10;
    }
    return best;
}

// Offset and drift together around `m`: nested 21 x 21 grids over a +-a_half, d +-d_half,
// shrinking to +-2 steps around the best until the offset step and the drift's effect over
// the run are below `finest`.
Line refine_jointly(const CumulativeEnergy& ce, const std::vector<Span>& spans, Line m, double a_half, double d_half, double span_s, double finest) {
    const double a_lo = m.a - a_half, a_hi = m.a + a_half, d_lim = d_half;
    for (int iter = 0; iter < 40; ++iter) {
        const double a_step = a_half / 10, d_step = d_half / 10;
        Line best = m;
        double best_c = score(ce, spans, m);
        for (int i = -10; i <= 10; ++i)
            for (int j = -10; j <= 10; ++j) {
                const Line c{std::clamp(m.a + i * a_step, a_lo, a_hi), std::clamp(m.d + j * d_step, -d_lim, d_lim), m.tc};
                const double v = score(ce, spans, c);
                if (v > best_c) best_c = v, best = c;
            }
        m = best;
        if (a_step <= finest && d_step * span_s <= finest) break;
        a_half = std::max(2 * a_step, finest), d_half = std::max(2 * d_step, finest / span_s);
    }
    return m;
}

// The spans of busy rows [first, last] of `spans` with the idle rows between them, guarded by
// half of the idle row on either side (so a small shift moves idle, not a neighbour's edge, in).
std::vector<Span> segment(const std::vector<Span>& spans, std::size_t first, std::size_t last) {
    std::vector<Span> out;
    if (first > 0 && !spans[first - 1].busy) out.push_back({0.5 * (spans[first - 1].start + spans[first - 1].end), spans[first - 1].end, false, false});
    out.insert(out.end(), spans.begin() + static_cast<std::ptrdiff_t>(first), spans.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    if (last + 1 < spans.size() && !spans[last + 1].busy) out.push_back({spans[last + 1].start, 0.5 * (spans[last + 1].start + spans[last + 1].end), false, false});
    return out;
}

// Crystal clocks disagree by tens of ppm; more than this is not a clock but a misfit.
constexpr double kMaxDrift = 1e-3;

double median_dt(const PowerTrace& tr) {
    std::vector<double> d;
    for (std::size_t i = 1; i < tr.size(); ++i) d.push_back(tr.t[i] - tr.t[i - 1]);
    if (d.empty()) return 0;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return d[d.size() / 2];
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b, c);
    return buf;
}

}  // namespace

Alignment align_auto(const PowerTrace& tr, const MarkerFile& markers, const AlignOptions& o) {
    validate_trace(tr);
    std::vector<Span> spans;
    double min_len = 1e300, busy_total = 0;
    for (const auto& r : markers.rows) {
        const double s = (o.realtime ? r.real_start_ns : r.mono_start_ns) * 1e-9, e = (o.realtime ? r.real_end_ns : r.mono_end_ns) * 1e-9;
        spans.push_back({s, e, r.kind != "idle", r.kind == "sync"});
        if (e > s) min_len = std::min(min_len, e - s);
        if (r.kind != "idle") busy_total += e - s;
    }
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.start < b.start; });
    if (spans.empty() || busy_total <= 0) throw Error("align: the marker file has no busy interval (sync or frame) to align on");
    // Time between rows that no row covers is idle (marker files without idle rows).
    for (std::size_t i = 1; i < spans.size(); ++i)
        if (spans[i].start > spans[i - 1].end) spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(i), Span{spans[i - 1].end, spans[i].start, false, false}), ++i;
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
    // The frame pattern is periodic: drift and window searches stay within 0.4 frame period.
    std::vector<double> starts, gaps;
    for (const auto& s : spans)
        if (s.busy && !s.sync) starts.push_back(s.start);
    if (starts.size() < 3) {
        starts.clear();
        for (const auto& s : spans)
            if (s.busy) starts.push_back(s.start);
    }
    for (std::size_t i = 1; i < starts.size(); ++i) gaps.push_back(starts[i] - starts[i - 1]);
    const double period = gaps.size() >= 2 ? median(gaps) : span_s;
    const double half = std::min(0.4 * period, std::max(5 * dt, 0.002 * span_s));

    // Coarse grid over every feasible offset, then the strongest local maxima refined: the true
    // peak is narrow (frames of unequal length line up only there), so a coarse point beside
    // it can score below a broad wrong peak; refining only the best coarse point would lock on that.
    auto drift_free = [&](double off) { return score(ce, spans, Line{off, 0, 0}); };
    const double coarse_step = std::max({min_len / 3, (hi - lo) / 20000, finest});
    std::vector<std::pair<double, double>> coarse;
    for (long i = 0, n = static_cast<long>(std::floor((hi - lo) / coarse_step + 1e-9)); i <= n; ++i)
        coarse.push_back({lo + i * coarse_step, drift_free(lo + i * coarse_step)});
    std::vector<std::size_t> peaks;
    for (std::size_t i = 0; i < coarse.size(); ++i)
        if ((i == 0 || coarse[i].second >= coarse[i - 1].second) && (i + 1 == coarse.size() || coarse[i].second >= coarse[i + 1].second)) peaks.push_back(i);
    std::sort(peaks.begin(), peaks.end(), [&](std::size_t a, std::size_t b) { return coarse[a].second > coarse[b].second; });
    peaks.resize(std::min<std::size_t>(peaks.size(), 16));
    std::vector<std::pair<double, double>> candidates;  // refined offset, score
    for (const std::size_t p : peaks) {
        const double x = search(drift_free, std::max(lo, coarse[p].first - 2 * coarse_step), std::min(hi, coarse[p].first + 2 * coarse_step),
                                coarse_step / 10, finest, out.step_s);
        candidates.push_back({x, drift_free(x)});
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    const double global = candidates.front().first;

    // Offset and drift jointly over the whole run, the drift bounded so the run's ends move at
    // most `half` against its centre.
    // Drift is measured by the busy edges only (lead idle rows carry none): from the first busy
    // start to the last busy end, referred to their centre.
    double edges_from = 1e300, edges_to = -1e300;
    for (const auto& s : spans)
        if (s.busy) edges_from = std::min(edges_from, s.start), edges_to = std::max(edges_to, s.end);
    const double edge_span = std::max(edges_to - edges_from, finest), tc = 0.5 * (edges_from + edges_to);
    Line m = refine_jointly(ce, spans, Line{global, 0, tc}, std::max(2 * coarse_step, 2 * finest), std::min(kMaxDrift, 2 * half / edge_span), edge_span, finest);
    // Edges are located only to within their sample interval, so a drift whose effect over the
    // run stays below one sample period is indistinguishable from none (on an exactly aligned
    // log the fit otherwise reports hundreds of ppm): it is not applied.
    const double fitted_drift = m.d;
    const bool drift_resolved = std::abs(m.d) * edge_span >= dt;
    if (!drift_resolved) m = Line{global, 0, tc};
    out.contrast_w = contrast(ce, spans, m);

    // Windows: each searched for its own offset on the fitted drift; their scatter about the
    // line is the residual (a drift that is not linear, or an edge the model misses).
    std::vector<std::size_t> busy_idx;
    for (std::size_t i = 0; i < spans.size(); ++i)
        if (spans[i].busy) busy_idx.push_back(i);
    const int windows = std::clamp(static_cast<int>(busy_idx.size() / 6), 1, std::max(1, o.windows));
    double ss = 0;
    for (int k = 0; k < windows && windows > 1; ++k) {
        const std::size_t bf = busy_idx.size() * k / windows, bl = busy_idx.size() * (k + 1) / windows - 1;
        const std::vector<Span> seg = segment(spans, busy_idx[bf], busy_idx[bl]);
        const double centre = 0.5 * (seg.front().start + seg.back().end);
        double step = 0;
        const double best_d = search([&](double dd) { return score(ce, seg, Line{m.a + dd, m.d, m.tc}); }, -half, half, std::max(half / 200, finest), finest, step);
        out.window_time_s.push_back(centre);
        out.window_offset_s.push_back(m.a + m.d * (centre - m.tc) + best_d);
        ss += best_d * best_d;
    }
    if (!out.window_offset_s.empty()) out.residual_s = std::sqrt(ss / static_cast<double>(out.window_offset_s.size()));

    // Confidence: the best offset at least half a frame period from the estimate, refined.
    double second = 0, second_c = -1e300;
    for (const auto& [off, c] : candidates)
        if (std::abs(off - global) >= 0.5 * period && c > second_c) second_c = c, second = off;
    if (second_c > -1e300) {
        const Line alt{m.a + (second - global), m.d, m.tc};
        out.second_contrast_w = contrast(ce, spans, alt);
        out.candidate_ratio = out.contrast_w > 0 ? out.second_contrast_w / out.contrast_w : 1;
        out.second_offset_s = alt.a;  // converted with the mapping below
        std::size_t sf = spans.size(), sl = 0;
        for (std::size_t i = 0; i < spans.size(); ++i)
            if (spans[i].sync) sf = std::min(sf, i), sl = i;
        if (sf < spans.size()) {
            const std::vector<Span> sync = segment(spans, sf, sl);
            out.has_sync = true;
            out.sync_contrast_w = contrast(ce, sync, m);
            out.sync_ratio = out.sync_contrast_w > 0 ? contrast(ce, sync, alt) / out.sync_contrast_w : 1;
        }
    } else {
        out.has_sync = std::any_of(spans.begin(), spans.end(), [](const Span& s) { return s.sync; });
    }
    out.ambiguous = !(out.contrast_w > 0) ||
                    (out.candidate_ratio >= kAmbiguousRatio && (!out.has_sync || out.sync_ratio >= kAmbiguousRatio)) ||
                    (out.has_sync && out.sync_ratio >= 1);

    // Back to absolute clocks with the drift referred to the first row:
    // t_trace = t + offset + drift * (t - marker_ref).
    ClockMapping cm;
    cm.realtime = o.realtime;
    cm.drift = m.d;
    cm.ref_s = marker_ref;
    cm.offset_s = m.a - m.d * m.tc + shift;
    out.second_offset_s += -m.d * m.tc + shift;
    for (auto& x : out.window_offset_s) x += shift;  // local offsets at the window centres, absolute
    for (auto& x : out.window_time_s) x += marker_ref;
    out.mapping = cm;
    out.confidence = fmt("contrast %.4g W", out.contrast_w);
    if (second_c > -1e300)
        out.confidence += fmt("; best alternative %+.4g ms away fits %.3f as well", 1e3 * (out.second_offset_s - cm.offset_s), out.candidate_ratio);
    else
        out.confidence += "; no alternative >= half a frame period away in the search range";
    if (out.has_sync) out.confidence += fmt("; sync pattern contrast %.4g W, %.3f of it at the alternative", out.sync_contrast_w, out.sync_ratio);
    else out.confidence += "; no sync pattern";
    if (!drift_resolved && fitted_drift != 0)
        out.confidence += fmt("; fitted drift %.3g ppm moves the run's ends by less than a sample period: not applied", 1e6 * fitted_drift);
    out.confidence += fmt("; window residual %.3g ms", 1e3 * out.residual_s);
    out.confidence += out.ambiguous ? " -> AMBIGUOUS" : " -> unambiguous";
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
