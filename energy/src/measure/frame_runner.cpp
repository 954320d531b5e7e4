#include "trn/energy/frame_runner.hpp"

#include <time.h>

#include <thread>

#include "trn/error.hpp"

namespace trn::energy {

ClockPair now_both() {
    timespec m{}, r{};
    clock_gettime(CLOCK_MONOTONIC, &m);
    clock_gettime(CLOCK_REALTIME, &r);
    return {static_cast<std::int64_t>(m.tv_sec) * 1000000000 + m.tv_nsec, static_cast<std::int64_t>(r.tv_sec) * 1000000000 + r.tv_nsec};
}

namespace {

FrameMarker row(const std::string& kind, int id, ClockPair a, ClockPair b) {
    FrameMarker m;
    m.kind = kind, m.id = id;
    m.mono_start_ns = a.mono_ns, m.mono_end_ns = b.mono_ns, m.real_start_ns = a.real_ns, m.real_end_ns = b.real_ns;
    return m;
}

void idle(MarkerFile& out, int& idle_id, double seconds) {
    if (seconds <= 0) return;
    const ClockPair a = now_both();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    out.rows.push_back(row("idle", idle_id++, a, now_both()));
}

// Runs the kernel back to back for at least `seconds` (a sync burst).
void burst(MarkerFile& out, int id, double seconds, const FrameKernel& kernel) {
    const ClockPair a = now_both();
    const std::int64_t until = a.mono_ns + static_cast<std::int64_t>(seconds * 1e9);
    do kernel();
    while (now_both().mono_ns < until);
    out.rows.push_back(row("sync", id, a, now_both()));
}

}  // namespace

MarkerFile run_frames(const FrameKernel& kernel, const FrameRunConfig& c) {
    if (c.frames <= 0) throw Error("run_frames: frames must be positive, got " + std::to_string(c.frames));
    if (c.idle_s < 0 || c.lead_idle_s < 0 || c.sync_unit_s < 0) throw Error("run_frames: idle and sync times must not be negative");
    MarkerFile out;
    out.meta = c.meta;
    out.meta["frames"] = std::to_string(c.frames);
    out.meta["idle_s"] = std::to_string(c.idle_s);
    out.meta["sync_unit_s"] = std::to_string(c.sync_unit_s);
    int idle_id = 0;
    idle(out, idle_id, c.lead_idle_s);
    if (c.sync_unit_s > 0) {
        const double pattern[] = {3, 1, 2};
        for (int i = 0; i < 3; ++i) {
            burst(out, i, pattern[i] * c.sync_unit_s, kernel);
            idle(out, idle_id, c.sync_unit_s);
        }
    }
    for (int k = 0; k < c.frames; ++k) {
        const ClockPair a = now_both();
        const PhaseTimes t = kernel();
        FrameMarker m = row("frame", k, a, now_both());
        m.write_ms = t.upload_ms, m.exec_ms = t.execute_ms, m.read_ms = t.download_ms;
        out.rows.push_back(m);
        idle(out, idle_id, k + 1 < c.frames ? c.idle_s : c.lead_idle_s);
    }
    return out;
}

}  // namespace trn::energy
