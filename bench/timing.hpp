#pragma once
// Per-iteration bookkeeping shared by every benchmark: manual time, phase times, allocations,
// and rate counters computed from the manual time (Google Benchmark's own kIsRate divides by the
// main thread's CPU time, which is wrong for OpenMP and device work).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <set>
#include <string>

#include "alloc_counter.hpp"
#include "trn/scoring.hpp"

namespace trn::bench {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Google Benchmark calls a benchmark function several times (iteration estimate, repetitions);
// the untimed warm-up call is only needed the first time, and repeating it on slow cases doubles
// the run. True once per key.
inline bool first_time(const std::string& key) {
    static std::set<std::string> seen;
    return seen.insert(key).second;
}

class IterationLog {
public:
    explicit IterationLog(benchmark::State& state) : state_(state), allocs_at_start_(allocation_count()) {}

    // One timed call: wall seconds measured around it, its phases, and whether the phases come
    // from a device clock (then their sum is the iteration's time).
    void add(double wall_s, const PhaseTimes& phases, bool device_clock) {
        const double device_s = phases.total_ms() / 1e3;
        const double t = device_clock && device_s > 0 ? device_s : wall_s;
        state_.SetIterationTime(t);
        seconds_ += t;
        wall_s_ += wall_s;
        upload_ms_ += phases.upload_ms, execute_ms_ += phases.execute_ms, download_ms_ += phases.download_ms;
    }
    // Timed work without phases (peers, STREAM).
    void add(double wall_s) { add(wall_s, PhaseTimes{}, false); }

    // Sets the counters; `items_per_iter` are named by `unit` ("Mpix/s" -> divided by 1e6).
    void finish(double bytes_per_iter, double items_per_iter, const std::string& unit, double unit_scale,
                double samples_per_iter = 0) {
        const double iters = static_cast<double>(state_.iterations());
        if (iters == 0 || seconds_ <= 0) return;
        const std::uint64_t allocs = allocation_count() - allocs_at_start_;
        state_.counters[unit] = items_per_iter * iters / seconds_ / unit_scale;
        if (bytes_per_iter > 0) state_.counters["GB/s"] = bytes_per_iter * iters / seconds_ / 1e9;
        if (samples_per_iter > 0) state_.counters["Msamples/s"] = samples_per_iter * iters / seconds_ / 1e6;
        // The kernel's own memory rate (device phases only), set beside the device's copy bandwidth.
        if (bytes_per_iter > 0 && execute_ms_ > 0) state_.counters["exec_GB/s"] = bytes_per_iter * iters / (execute_ms_ / 1e3) / 1e9;
        state_.counters["write_ms"] = upload_ms_ / iters;
        state_.counters["exec_ms"] = execute_ms_ / iters;
        state_.counters["read_ms"] = download_ms_ / iters;
        state_.counters["wall_ms"] = wall_s_ * 1e3 / iters;
        state_.counters["allocs_per_iter"] = double(allocs) / iters;
    }

private:
    benchmark::State& state_;
    std::uint64_t allocs_at_start_;
    double seconds_ = 0, wall_s_ = 0, upload_ms_ = 0, execute_ms_ = 0, download_ms_ = 0;
};

}  // namespace trn::bench
