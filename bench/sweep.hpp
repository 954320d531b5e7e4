#pragma once
// Which cases a run registers: a quick default subset (the under-two-minutes report) or the full
// sweep from issue 6. Chosen by --trn_full on the command line (taken out before Google Benchmark
// sees the arguments).
#include <cstddef>
#include <string>
#include <vector>

namespace trn::bench {

struct FrameSize {
    int width, height;
    std::string text() const { return std::to_string(width) + "x" + std::to_string(height); }
};

struct Sweep {
    bool full = false;
    std::vector<FrameSize> sobel_sizes;        // every device, hot
    std::vector<FrameSize> sobel_cold_sizes;   // every device, cold
    FrameSize sobel_reference_size{640, 480};  // the only size cpu-ref runs (slow by design)
    bool sobel_batch16 = false;                // 16 frames per iteration on opencl/vulkan devices
    std::vector<int> ncc_counts;               // particles per call
    std::vector<FrameSize> ncc_templates;
    FrameSize ncc_filter_template{160, 120};   // the particle filter's case (issue 14): this template, dense,
    int ncc_filter_count = 1000;               // this many particles, every backend and the old cpu path
    int ncc_reference_count = 100;             // cpu-ref and the per-particle peers run this many
                                               // (their per-particle rate does not depend on it)
    std::size_t latency_steps = 0;             // frame to MAVLink message: steps of the real flight per pass (0: all)
    std::size_t cold_bytes = 0;                // rotating working set for "cold" cases
    std::string cold_basis;                    // why that size, e.g. "4x the reported 508 MiB L3"
};

Sweep make_sweep(bool full);

// The size of the rotating working set: $TRN_BENCH_COLD_MB if set, else 4x the reported
// last-level cache, at least 256 MiB and at most a quarter of physical memory; `basis` says which.
std::size_t cold_working_set_bytes(std::string& basis);

// The rule without the environment: `llc` and `physical` in bytes (0: not reported).
std::size_t cold_working_set_bytes(std::size_t llc, std::size_t physical, std::string& basis);

}  // namespace trn::bench
