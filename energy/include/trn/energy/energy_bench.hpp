#pragma once
// `trnkit energy bench` as a library call: the frame runner (Algorithm 3) on each target in turn
// while a BackgroundSampler records power on CLOCK_MONOTONIC in this process, then every target's
// markers integrated against that one trace (same clock: no alignment). The result joins speed
// (frames/s) and energy (J/frame gross and net of idle, with the integration bound and a 95 % CI)
// per target and platform. The idle baseline is each run's lead idle phase (plus its gaps).
#include <map>
#include <string>
#include <vector>

#include "trn/energy/frame_runner.hpp"
#include "trn/energy/power_sampler.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct BenchTarget {
    std::string name;                          // "cpu", "opencl:0": a backend spec
    FrameKernel kernel;                        // one frame of work
    std::map<std::string, std::string> meta;   // marker header: backend, device, kernel, size, ...
};

struct BenchConfig {
    FrameRunConfig run;          // frames, gaps, lead idle (the baseline phase), sync pattern
    double period_s = 0.002;     // sampler period
    std::string platform;        // label of this machine; rows are "<platform>:<backend/kernel/size>"
    IntegrationOptions integration;
    // Kernel calls inside one frame (the targets' kernels make them): a sampler slower than one
    // call still sees whole frames. Row figures are per call; run reports stay per frame.
    int calls_per_frame = 1;
};

struct BenchRow {
    std::string platform, target;
    std::size_t frames = 0, usable = 0;
    int calls_per_frame = 1;                  // the figures below are per call (frame / calls)
    double frame_ms = 0, exec_ms = 0;         // means over usable frames (marker clock, backend clock)
    double frames_per_s = 0;                  // 1000 / frame_ms: back-to-back throughput
    double gross_j = 0, net_j = 0;            // means per usable frame
    double gross_ci_low = 0, gross_ci_high = 0, net_ci_low = 0, net_ci_high = 0;  // 95 % CI of the means
    double bound_j = 0;                       // mean per-frame integration bound (error_j)
    double idle_w = 0, busy_w = 0;            // baseline; gross power while a frame runs
    double samples_per_frame = 0;
    RunReport run;                            // the full report (what `energy integrate` writes)
    MarkerFile markers;
};

struct BenchResult {
    std::string sampler;       // PowerSampler::describe()
    double period_s = 0;
    PowerTrace trace;          // the whole bench on CLOCK_MONOTONIC
    std::vector<BenchRow> rows;
    std::vector<std::string> warnings;
};

// Throws trn::Error for no targets, a failing sampler (naming it) or a failing kernel (naming the
// target). A target whose frames are all flagged (too few samples) is kept with usable = 0.
BenchResult run_energy_bench(PowerSampler& sampler, const std::vector<BenchTarget>& targets, const BenchConfig& config);

// Row figures from a run report (exposed for tests and for reports integrated later).
BenchRow bench_row(const RunReport& run, const std::string& platform, const std::string& target, int calls_per_frame = 1);

std::string bench_json(const BenchResult& result);      // "trnkit_energy_bench": 1, rows, config, warnings
std::string bench_csv(const BenchResult& result);       // one line per row
std::string bench_markdown(const BenchResult& result);  // the table people read
// bench_energy.png (J/frame, gross and net, with bounds), bench_speed.png (frames/s), each with
// its .gp/.dat, in `folder` (trn/io/gnuplot.hpp).
void plot_bench(const BenchResult& result, const std::string& folder);

}  // namespace trn::energy
TRN_API_END
