#include "trn/energy/power_sampler.hpp"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "sources/raspberry_pi/pi_pmic.hpp"
#include "trn/energy/nvml_sampler.hpp"
#include "trn/energy/sysfs_sampler.hpp"
#include "trn/error.hpp"

namespace trn::energy {

std::unique_ptr<PowerSampler> make_power_sampler(const std::string& spec, const SamplerOptions& o) {
    if (spec.rfind("nvml:", 0) == 0 || spec == "nvml") return std::make_unique<NvmlSampler>(parse_nvml_spec(spec), o.nvml_library);
    if (spec.rfind("hwmon:", 0) == 0 || spec.rfind("rapl:", 0) == 0) return std::make_unique<SysfsSampler>(find_sysfs_source(spec, o.sysfs_root));
    if (spec == "pmic:vcgencmd" || spec == "pmic") return pmic::make_sampler(o.vcgencmd);
    throw Error("power source '" + spec + "': expected hwmon:NAME[:CHANNEL], rapl:NAME, nvml:INDEX[:power|:energy] or pmic:vcgencmd");
}

std::vector<std::string> list_power_sources(const SamplerOptions& o) {
    std::vector<std::string> out;
    for (const auto& s : list_sysfs_sources(o.sysfs_root)) out.push_back(s.describe());
    if (access(o.vcgencmd.c_str(), X_OK) == 0) out.push_back("pmic:vcgencmd (" + o.vcgencmd + " pmic_read_adc: a Raspberry Pi 5's PMIC rails)");
    try {
        for (const auto& d : list_nvml_devices(o.nvml_library)) out.push_back(d);
    } catch (const Error& e) {
        out.push_back(std::string("nvml: not available (") + e.what() + ")");
    }
    return out;
}

double clock_seconds(SampleClock clock) {
    timespec ts{};
    clock_gettime(clock == SampleClock::Monotonic ? CLOCK_MONOTONIC : CLOCK_REALTIME, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

PowerTrace sample_for(PowerSampler& sampler, double period_s, double duration_s, SampleClock clock) {
    if (!(period_s > 0) || !(duration_s > 0)) throw Error(sampler.describe() + ": sampling period and duration must be positive");
    // Due times come from steady_clock so a wall-clock step cannot stretch or stop the loop.
    // A poll that comes late skips the slots it missed (no bursts of polls microseconds apart,
    // whose interval means a counter's step would dominate); skips are counted in the notes.
    using steady = std::chrono::steady_clock;
    const auto start = steady::now();
    std::size_t late = 0;
    for (long k = 0;;) {
        const auto due = start + std::chrono::duration_cast<steady::duration>(std::chrono::duration<double>(k * period_s));
        if (due - start > std::chrono::duration<double>(duration_s)) break;
        std::this_thread::sleep_until(due);
        sampler.poll(clock_seconds(clock));
        const long next = static_cast<long>(std::chrono::duration<double>(steady::now() - start).count() / period_s) + 1;
        if (next > k + 1) ++late;
        k = std::max(k + 1, next);
    }
    PowerTrace tr = sampler.trace();
    tr.wall_clock = clock == SampleClock::Realtime;
    if (late) tr.notes.push_back(std::to_string(late) + " poll(s) more than one period late (a loaded machine); the missed ones were skipped");
    return tr;
}

}  // namespace trn::energy
