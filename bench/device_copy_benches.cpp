// The memory-bandwidth limit of each device backend, measured on the device itself:
// trn::measure_copy_bandwidth (clEnqueueCopyBuffer / vkCmdCopyBuffer between two device
// buffers, device clock). Bytes counted as STREAM's copy counts them (read + written). The host's
// limit, for the cpu backends, is stream/copy (stream_benches.cpp).
// Names: devcopy/<MiB>MiB/dev:NAME. 256 MiB per buffer: over 4x the largest GPU L2 we target
// (H200: 60 MiB), so the copy runs from device memory, not cache.
#include <benchmark/benchmark.h>

#include "devices.hpp"
#include "register.hpp"
#include "trn/copy_bandwidth.hpp"

namespace trn::bench {
namespace {

constexpr std::size_t kCopyBytes = std::size_t(256) << 20;
constexpr int kCopiesPerCall = 10;

void device_copy(benchmark::State& state, DeviceEntry dev) {
    Backend& backend = backend_for(dev.name);
    CopyBandwidth last;
    for (auto _ : state) {
        last = measure_copy_bandwidth(backend, kCopyBytes, kCopiesPerCall);
        state.SetIterationTime(last.best_seconds);
    }
    state.counters["GB/s"] = last.bytes_per_second / 1e9;
    state.counters["median_GB/s"] = 2.0 * double(last.bytes) / last.median_seconds / 1e9;
    state.SetLabel(last.method + ", best of " + std::to_string(last.repetitions) + " copies of " +
                   std::to_string(kCopyBytes >> 20) + " MiB");
}

}  // namespace

void register_device_copy_benchmarks(const Sweep&) {
    for (const DeviceEntry& dev : bench_devices()) {
        if (!has_device_clock(dev.family)) continue;
        benchmark::RegisterBenchmark(("devcopy/" + std::to_string(kCopyBytes >> 20) + "MiB/dev:" + dev.name).c_str(),
                                     device_copy, dev)
            ->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
    }
}

}  // namespace trn::bench
