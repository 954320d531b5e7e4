#pragma once
// Synthetic measurement runs for tests: a marker file with a known timeline and a power trace
// sampled on another clock (known offset and drift), where power is idle_w plus busy_w while a
// sync burst or frame runs. The true energy of every frame is therefore known exactly.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "trn/energy/markers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/energy/trace.hpp"

namespace trn::energy::test {

struct Timeline {
    MarkerFile markers;
    double t0 = 1.7e9;  // marker clock (UNIX seconds) of the first row
};

// lead idle, sync bursts 3u,1u,2u with u gaps (none when sync_u is 0), then frames of frame_s
// (+ a deterministic wobble of +-`wobble` x frame_s so frames differ; 0: strictly periodic)
// separated by idle_s.
inline Timeline make_timeline(int frames, double frame_s, double idle_s, double sync_u = 0.1, double lead_s = 0.5, double wobble = 0.1) {
    Timeline tl;
    double t = tl.t0;
    auto add = [&](const char* kind, int id, double len) {
        FrameMarker m;
        m.kind = kind, m.id = id;
        m.real_start_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
        m.real_end_ns = static_cast<std::int64_t>(std::llround((t + len) * 1e9));
        m.mono_start_ns = m.real_start_ns - 1'690'000'000'000'000'000, m.mono_end_ns = m.real_end_ns - 1'690'000'000'000'000'000;
        m.exec_ms = kind[0] == 'f' ? len * 1e3 : 0;
        tl.markers.rows.push_back(m);
        t += len;
    };
    int idle = 0;
    add("idle", idle++, lead_s);
    const double pattern[] = {3, 1, 2};
    for (int i = 0; i < 3 && sync_u > 0; ++i) add("sync", i, pattern[i] * sync_u), add("idle", idle++, sync_u);
    for (int k = 0; k < frames; ++k) add("frame", k, frame_s * (1 + wobble * std::sin(k * 1.7))), add("idle", idle++, k + 1 < frames ? idle_s : lead_s);
    tl.markers.meta = {{"backend", "synthetic"}, {"kernel", "sobel"}};
    return tl;
}

// Power on the trace clock tau, where tau = t + offset + drift*(t - ref) for marker time t.
struct TraceClock {
    double offset = 0, drift = 0, ref = 0;
    double to_marker(double tau) const { return (tau - offset + drift * ref) / (1 + drift); }
};

inline bool busy_at(const MarkerFile& m, double t) {
    for (const auto& r : m.rows)
        if (r.kind != "idle" && t >= r.real_start_ns * 1e-9 && t < r.real_end_ns * 1e-9) return true;
    return false;
}

// Samples every dt on the trace clock from tau_begin to tau_end; `noise_w` adds a deterministic
// +-noise pattern.
inline PowerTrace sample_trace(const MarkerFile& m, const TraceClock& c, double tau_begin, double tau_end, double dt, double idle_w, double busy_w,
                               double noise_w = 0, bool wall_clock = false) {
    PowerTrace tr;
    tr.source = "synthetic", tr.format = "trnkit", tr.quantity = "power", tr.wall_clock = wall_clock;
    std::uint64_t s = 12345;
    for (double tau = tau_begin; tau <= tau_end; tau += dt) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        const double n = noise_w * ((static_cast<double>(s % 2001) / 1000.0) - 1.0);
        tr.t.push_back(tau);
        tr.w.push_back(idle_w + (busy_at(m, c.to_marker(tau)) ? busy_w : 0) + n);
    }
    return tr;
}

// A run report with the given per-frame energies (J, gross = net), for comparisons whose
// input values are chosen directly; distinct `log_hash`es keep compare from refusing repeats.
inline RunReport report_with_energies(const std::string& platform, const std::vector<double>& joules, const std::string& log_hash) {
    RunReport r;
    r.platform = platform, r.log_sha256 = log_hash, r.markers_sha256 = "m";
    for (std::size_t i = 0; i < joules.size(); ++i) {
        ReportFrame f;
        f.energy.id = static_cast<int>(i), f.energy.gross_j = f.energy.net_j = joules[i], f.marker_ms = 5 + 0.1 * static_cast<double>(i % 7);
        r.frames.push_back(f);
    }
    return r;
}

}  // namespace trn::energy::test
