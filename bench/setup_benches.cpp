// Backend start-up, measured apart from every throughput loop: creating the backend (which builds
// or loads its kernels) plus the first upload_map / score / sobel on tiny inputs.
// "first" is the first creation in this process: a cold build when the kernel caches are empty
// (scripts/bench-report points XDG_CACHE_HOME and POCL_CACHE_DIR at a fresh folder for this);
// "cached" creates the backend again, so caches filled by "first" are used.
// Names: setup/<dev:NAME>/<first|cached>.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <set>

#include "backend_env.hpp"  // the TRN_* variables -> BackendOptions, as the CLI reads them
#include "devices.hpp"
#include "register.hpp"
#include "timing.hpp"
#include "trn/registry.hpp"

namespace trn::bench {
namespace {

struct StartTimes {
    double create_s = 0, first_calls_s = 0;
};

StartTimes start_backend(const std::string& name) {
    std::vector<std::uint8_t> map(256 * 256), templ(32 * 32);
    for (std::size_t i = 0; i < map.size(); ++i) map[i] = static_cast<std::uint8_t>((i * 7919) >> 5);
    for (std::size_t i = 0; i < templ.size(); ++i) templ[i] = static_cast<std::uint8_t>((i * 104729) >> 3);
    std::vector<Pose> poses(8, Pose{128, 128, 0.1f, 1.0f});
    std::vector<ParticleScore> scores(poses.size());
    std::vector<std::int16_t> gx(64 * 64), gy(64 * 64);

    StartTimes t;
    const auto t0 = Clock::now();
    auto backend = default_registry().create(name, test::backend_options_from_environment());
    t.create_s = seconds_since(t0);
    const auto t1 = Clock::now();
    const MapHandle h = backend->upload_map({map.data(), 256, 256, 256});
    backend->score(h, GrayView{templ.data(), 32, 32, 32}, poses, ScoreOptions{}, scores);
    backend->sobel({map.data(), 64, 64, 256}, {gx.data(), 64, 64, 64}, {gy.data(), 64, 64, 64});
    t.first_calls_s = seconds_since(t1);
    return t;
}

std::string cache_description() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* pocl = std::getenv("POCL_CACHE_DIR");
    return std::string("XDG_CACHE_HOME=") + (xdg ? xdg : "(unset)") + ", POCL_CACHE_DIR=" + (pocl ? pocl : "(unset)");
}

void setup_first(benchmark::State& state, std::string name) {
    static std::set<std::string> measured;
    if (!measured.insert(name).second) {
        state.SkipWithError("the first creation happens once per process; run with --benchmark_repetitions=1 for setup/");
        for (auto _ : state) {
        }
        return;
    }
    StartTimes t;
    for (auto _ : state) {
        t = start_backend(name);
        state.SetIterationTime(t.create_s + t.first_calls_s);
    }
    state.counters["create_ms"] = t.create_s * 1e3;
    state.counters["first_calls_ms"] = t.first_calls_s * 1e3;
    state.SetLabel(cache_description());
}

void setup_cached(benchmark::State& state, std::string name) {
    double create = 0, first = 0;
    for (auto _ : state) {
        const StartTimes t = start_backend(name);
        create += t.create_s, first += t.first_calls_s;
        state.SetIterationTime(t.create_s + t.first_calls_s);
    }
    const double iters = double(state.iterations());
    state.counters["create_ms"] = create / iters * 1e3;
    state.counters["first_calls_ms"] = first / iters * 1e3;
    state.SetLabel(cache_description());
}

}  // namespace

void register_setup_benchmarks(const Sweep&) {
    for (const DeviceEntry& dev : bench_devices()) {
        if (dev.family == "cpu-ref") continue;
        benchmark::RegisterBenchmark(("setup/dev:" + dev.name + "/first").c_str(), setup_first, dev.name)
            ->UseManualTime()->Iterations(1)->Repetitions(1)->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("setup/dev:" + dev.name + "/cached").c_str(), setup_cached, dev.name)
            ->UseManualTime()->Iterations(3)->Repetitions(1)->Unit(benchmark::kMillisecond);
    }
}

}  // namespace trn::bench
