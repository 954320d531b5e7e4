// Frame to MAVLink message, per backend (issue 43 item 5): the wall time from handing a real camera
// frame to the online Localizer until the MAVLink v2 bytes of that step's messages are ready, as
// `trnkit localize --mavlink` makes them: the Localizer's step, the step's row, latitude/longitude,
// the NavFix (trn/localize/mavlink_fix.hpp) and the frames (HEARTBEAT when due, GPS_INPUT,
// GLOBAL_POSITION_SENSOR, ODOMETRY). No network: the bytes are not sent. Frame loading (and the
// levelling of a tilted frame, which the flight source does) comes before the hand-over and is not
// timed.
//
// The flight: $TRN_SHARED_DATA/realflight3/air, the one real flight with a geo origin (flight.json),
// so the one the CLI can stream (`--mavlink` is refused without latitude/longitude; realflight and
// realflight2 have none). Absent: the case reports an error saying so (visible, never a silent pass).
// Settings: the CLI's defaults (`trnkit localize --dataset ... --mavlink ...` with nothing else):
// profile ours, KLD 100..2000 particles (1000 fixed), logistic:0.2, a 50 m start prior at the first
// row's truth, frames area-downscaled to 160 px, seed 1, the folder's odometry and compass.
//
// One iteration = one pass over the flight (the quick sweep: its first 60 steps; --trn_full: all
// 167), on a fresh Localizer (its map upload not timed), one repetition; the first
// steps of a fresh Localizer run once untimed beforehand (kernels, lazy buffers). Counters: each
// step's latency, median and p95 (ms), the mean and the largest, the median of the part outside
// the Localizer's own step_ms (beyond_step_median_ms), and the ratios of median and p95 to the cpu
// backend's from this process (cpu is registered first; no ratio when it did not run).
// Names: latency/<flight>/frame-to-mavlink/dev:NAME (cpu-ref left out: the reference, not a
// flight backend; a pass would take minutes).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "devices.hpp"
#include "inputs.hpp"
#include "register.hpp"
#include "timing.hpp"
#include "trn/io/mavlink_stream.hpp"
#include "trn/localize/air_inputs.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/localize/mavlink_fix.hpp"

namespace trn::bench {
namespace {

constexpr double kCliRateHz = 5;           // trnkit localize --rate
constexpr std::size_t kWarmupSteps = 3;    // untimed, on a Localizer of their own

// A recorded flight read once (frames decoded and levelled), replayed from memory. next() stamps
// the moment it hands a sample over: the latency's start.
struct RecordedFlight {
    std::string name, folder;
    localize::AirInputs inputs;
    std::vector<filter::FlightSample> samples;
    std::size_t stride = 1;
};

class Replay : public filter::FlightSource {
public:
    Replay(const RecordedFlight& f, std::size_t limit) : flight_(f), limit_(std::min(limit, f.samples.size())) {}
    bool next(filter::FlightSample& s) override {
        if (next_ == limit_) return false;
        s = flight_.samples[next_++];
        handed_ = Clock::now();
        return true;
    }
    std::size_t frames_hint() const override { return limit_; }
    Clock::time_point handed() const { return handed_; }

private:
    const RecordedFlight& flight_;
    std::size_t limit_, next_ = 0;
    Clock::time_point handed_{};
};

const RecordedFlight* recorded_flight() {
    static const std::unique_ptr<RecordedFlight> flight = []() -> std::unique_ptr<RecordedFlight> {
        const std::filesystem::path folder = shared_data_path("realflight3/air");
        if (folder.empty() || !std::filesystem::exists(folder / "metadata.csv")) return nullptr;
        auto f = std::make_unique<RecordedFlight>();
        f->name = "realflight3", f->folder = folder.string();
        localize::AirInputOptions o;
        o.dataset = f->folder;
        f->inputs = localize::resolve_air_inputs(o);
        // As run_localization reads an AIR folder (the CLI's --rate 5 and --max-tilt-deg 10).
        const double fps = f->inputs.fps > 0 ? f->inputs.fps : kCliRateHz;
        f->stride = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(fps / kCliRateHz)));
        const std::size_t rows = filter::count_air_rows(f->folder);
        filter::AirFlightSource source(f->folder, f->inputs.camera, f->inputs.map.metres_per_pixel, fps, f->stride,
                                       (rows + f->stride - 1) / f->stride, {f->inputs.map.image.width, f->inputs.map.image.height},
                                       filter::kDefaultMaxTiltDeg);
        for (filter::FlightSample s; source.next(s);) f->samples.push_back(s);
        return f;
    }();
    return flight.get();
}

// `trnkit localize`'s configuration with no option given, on this flight: the defaults' one home
// (localizer_defaults.hpp; tests/python/test_defaults.py holds the CLI to it) and the flight's map and camera.
localize::LocalizerConfig cli_default_config(const RecordedFlight& f) {
    localize::LocalizerConfig c = localize::localizer_profile(filter::Profile::Ours);
    c.filter.metres_per_pixel = f.inputs.map.metres_per_pixel;
    c.camera_hfov_deg = f.inputs.camera.hfov_deg;
    return c;
}

struct Latencies {
    std::vector<double> ms;
    std::vector<double> beyond_step_ms;  // latency minus the Localizer's own step_ms (what processing_us leaves out)
    std::size_t fixes = 0, bytes = 0;
};

// One pass over the first `limit` steps on a fresh Localizer; each step's latency appended.
void fly(const RecordedFlight& f, Backend& backend, std::size_t limit, Latencies& out) {
    const sim::Map& map = f.inputs.map;
    localize::Localizer localizer(map.image.view(), map.metres_per_pixel, backend, cli_default_config(f), map.valid_view());
    Replay replay(f, limit);
    localize::NavFixMaker fixes(map.metres_per_pixel, /*compassless=*/false);
    io::mavlink::Stream stream;  // the CLI's defaults: every message, system 1, component 197, sensor 0
    const auto on_step = [&](const localize::LocalizationRow& r, const localize::Estimate& e) {
        localize::LocalizationRow row = r;  // as run_localization's hook for the CLI: with latitude/longitude
        const sim::LatLon ll = f.inputs.to_latlon(r.estimate_x, r.estimate_y);
        row.estimate_lat = ll.latitude_deg, row.estimate_lon = ll.longitude_deg;
        const io::mavlink::NavFix fix = fixes.fix(row, e);
        const std::vector<std::uint8_t> bytes = stream.step(fix);
        out.ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - replay.handed()).count());
        out.beyond_step_ms.push_back(out.ms.back() - e.step_ms);
        out.fixes += fix.valid, out.bytes += bytes.size();
        benchmark::DoNotOptimize(bytes.data());
    };
    localize::run_localization(replay, localizer, {}, on_step);
}

double percentile(std::vector<double> v, double q) {  // nearest rank
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t rank = static_cast<std::size_t>(std::ceil(q * double(v.size())));
    return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

struct Reference {
    double median_ms = NAN, p95_ms = NAN;
};
std::map<std::string, Reference>& cpu_reference() {  // per flight: the cpu backend's, from this process
    static std::map<std::string, Reference> r;
    return r;
}

void frame_to_mavlink(benchmark::State& state, DeviceEntry dev, std::size_t steps) {
    const RecordedFlight* f = recorded_flight();
    if (!f) {
        state.SkipWithError("no real flight: $TRN_SHARED_DATA/realflight3/air not found (the frame-to-message latency needs a georeferenced real flight)");
        for (auto _ : state) {
        }
        return;
    }
    if (!f->inputs.to_latlon) {
        state.SkipWithError((f->folder + ": no geo origin (flight.json); the CLI refuses --mavlink without one").c_str());
        for (auto _ : state) {
        }
        return;
    }
    Backend& backend = backend_for(dev.name);
    if (first_time("latency/" + dev.name)) {
        Latencies warm;
        fly(*f, backend, kWarmupSteps, warm);
    }
    const std::size_t limit = steps > 0 ? std::min(steps, f->samples.size()) : f->samples.size();
    Latencies all;
    for (auto _ : state) {
        const std::size_t before = all.ms.size();
        fly(*f, backend, limit, all);
        double pass = 0;
        for (std::size_t k = before; k < all.ms.size(); ++k) pass += all.ms[k];
        state.SetIterationTime(pass / 1e3);
    }
    const double median = percentile(all.ms, 0.5), p95 = percentile(all.ms, 0.95);
    double sum = 0;
    for (double v : all.ms) sum += v;
    state.counters["median_ms"] = median;
    state.counters["p95_ms"] = p95;
    state.counters["mean_ms"] = all.ms.empty() ? NAN : sum / double(all.ms.size());
    state.counters["max_ms"] = all.ms.empty() ? NAN : *std::max_element(all.ms.begin(), all.ms.end());
    state.counters["steps"] = double(all.ms.size());
    // The part of the latency outside Localizer::step's own wall time (Estimate::step_ms, which the
    // CLI sends as processing_us): the hand-over, the row, latitude/longitude and the encoding.
    state.counters["beyond_step_median_ms"] = percentile(all.beyond_step_ms, 0.5);
    state.counters["bytes_per_step"] = all.ms.empty() ? 0 : double(all.bytes) / double(all.ms.size());
    std::string ratio = "no cpu run in this process: no ratio";
    if (dev.family == "cpu") {
        cpu_reference()[f->name] = {median, p95};
        ratio = "the reference of the x_cpu ratios";
    } else if (const auto it = cpu_reference().find(f->name); it != cpu_reference().end()) {
        state.counters["median_x_cpu"] = median / it->second.median_ms;
        state.counters["p95_x_cpu"] = p95 / it->second.p95_ms;
        ratio = "x_cpu: this backend's median and p95 over the cpu backend's, same process";
    }
    state.SetLabel(backend.info().device + ", " + f->name + " " + (limit < f->samples.size() ? "first " : "") + std::to_string(limit) + " steps x " +
                   std::to_string(state.iterations()) + " pass(es), " + std::to_string(all.fixes) + " with a fix; CLI defaults; " + ratio);
}

}  // namespace

void register_latency_benchmarks(const Sweep& sweep) {
    std::vector<DeviceEntry> devices;
    for (const DeviceEntry& d : bench_devices())
        if (d.family != "cpu-ref") devices.push_back(d);
    // cpu first: the others' ratios need its figures from this process.
    std::stable_partition(devices.begin(), devices.end(), [](const DeviceEntry& d) { return d.family == "cpu"; });
    for (const DeviceEntry& dev : devices)
        benchmark::RegisterBenchmark(("latency/realflight3/frame-to-mavlink/dev:" + dev.name).c_str(), frame_to_mavlink, dev, sweep.latency_steps)
            ->UseManualTime()->Iterations(1)->Repetitions(1)->Unit(benchmark::kMillisecond);  // one pass: every step is a sample
}

}  // namespace trn::bench
