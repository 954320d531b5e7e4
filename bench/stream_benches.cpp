// STREAM-like copy and triad (McCalpin's kernels, OpenMP over every core): the memory-bandwidth
// limit that Sobel's compulsory traffic is measured against. Bytes counted as STREAM does
// (copy 16 B, triad 24 B per element; write-allocate reads not counted).
// Names: stream/<copy|triad>/cold (the three arrays together as large as the cold working set,
// >= 4x the reported last-level cache, see sweep.cpp).
// No "hot" variant: on 2 cores, OpenMP fork/join dominates arrays small enough for L2.
// One benchmark iteration repeats passes until the last few agree (stream_stats.hpp) and reports
// their median; counters: passes, pass_cv (variation of the last passes), unstable (1 when they
// never agreed within the pass budget: the report then marks the limit unreliable).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <memory>
#include <vector>

#include "register.hpp"
#include "stream_stats.hpp"
#include "timing.hpp"

namespace trn::bench {
namespace {

struct Arrays {
    std::size_t n;
    std::unique_ptr<double[]> a, b, c;
    explicit Arrays(std::size_t count) : n(count), a(new double[count]), b(new double[count]), c(new double[count]) {
        // First touch on the threads that later use each part (page placement).
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) a[i] = 1.0, b[i] = 2.0, c[i] = 0.0;
    }
};

enum class Kernel { Copy, Triad };

// Allocated and first-touched once: page faults on a fresh GiB cost seconds on the dev VM.
Arrays& arrays(std::size_t bytes_total) {
    static std::unique_ptr<Arrays> arr;
    const std::size_t n = bytes_total / 3 / sizeof(double);
    if (!arr || arr->n != n) {
        arr.reset();
        arr = std::make_unique<Arrays>(n);
    }
    return *arr;
}

void stream(benchmark::State& state, Kernel kernel, std::size_t bytes_total, std::string cold_basis) {
    Arrays& arr = arrays(bytes_total);
    double* a = arr.a.get();
    const double* b = arr.b.get();
    const double* c = arr.c.get();
    const long n = static_cast<long>(arr.n);
    const double s = 3.0;
    auto run = [&] {
        if (kernel == Kernel::Copy) {
#pragma omp parallel for schedule(static)
            for (long i = 0; i < n; ++i) a[i] = b[i];
        } else {
#pragma omp parallel for schedule(static)
            for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
        }
    };
    if (first_time(kernel == Kernel::Copy ? "stream/copy" : "stream/triad")) run();
    const double bytes = double(n) * sizeof(double) * (kernel == Kernel::Copy ? 2 : 3);
    const StabilityRule rule;
    std::vector<double> rates;  // GB/s of each pass
    rates.reserve(rule.max_passes);
    RateStats stats;
    IterationLog log(state);
    for (auto _ : state) {
        rates.clear();
        while (!enough_passes(rates, rule)) {
            const auto t0 = Clock::now();
            run();
            benchmark::ClobberMemory();
            rates.push_back(bytes / seconds_since(t0) / 1e9);
        }
        stats = summarize_rates(rates, rule);
        log.add(bytes / (stats.median * 1e9));  // the median pass stands for the iteration
    }
    log.finish(bytes, double(n), "Melem/s", 1e6);
    state.counters["passes"] = double(stats.samples);
    state.counters["pass_cv"] = stats.cv;
    state.counters["unstable"] = stats.stable ? 0 : 1;
    state.counters["max_cv"] = rule.max_cv;
    state.SetLabel(std::to_string(omp_get_max_threads()) + " threads, 3 arrays of " + std::to_string(n * sizeof(double) >> 20) +
                   " MiB (" + cold_basis + ")");
}

}  // namespace

void register_stream_benchmarks(const Sweep& sweep) {
    for (auto [kernel, name] : {std::pair{Kernel::Copy, "copy"}, std::pair{Kernel::Triad, "triad"}}) {
        benchmark::RegisterBenchmark((std::string("stream/") + name + "/cold").c_str(), stream, kernel, sweep.cold_bytes,
                                     sweep.cold_basis)
            ->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
    }
}

}  // namespace trn::bench
