#pragma once
// One interface over every live power source, so `energy sample`, `energy bench` and the
// background sampler thread treat hwmon, RAPL and NVML alike:
//   hwmon:NAME[:CHANNEL]   ina2xx / ina3221 under SYSFS_ROOT/class/hwmon   (sysfs_sampler.hpp)
//   rapl:NAME              powercap energy_uj under SYSFS_ROOT/class/powercap (sysfs_sampler.hpp)
//   nvml:INDEX[:power|:energy]  NVIDIA board power / total energy counter (nvml_sampler.hpp)
//   pmic:vcgencmd          Raspberry Pi 5 PMIC: `VCGENCMD pmic_read_adc` per poll, sum of rails I x V
// Paths are options passed by value (the library reads no environment), so tests point them at a
// fake sysfs tree and a fake NVML library.
#include <memory>
#include <string>
#include <vector>

#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct SamplerOptions {
    std::string sysfs_root = "/sys";
    std::string nvml_library = "libnvidia-ml.so.1";  // dlopen()ed at run time: no build dependency
    std::string vcgencmd = "/usr/bin/vcgencmd";       // pmic:vcgencmd runs it (absolute path, empty environment)
};

class PowerSampler {
public:
    virtual ~PowerSampler() = default;
    // "hwmon:ina3221:2 (/sys/class/hwmon/hwmon3)", "nvml:0:energy (NVIDIA ...)".
    virtual std::string describe() const = 0;
    // Reads the source once at t_s (seconds on the caller's clock, strictly increasing); throws
    // trn::Error naming the source when a read fails.
    virtual void poll(double t_s) = 0;
    // Everything polled so far (interval-mean sources start at their first poll), with notes.
    // Whoever chose the clock of t_s sets wall_clock (sample_for, BackgroundSampler do).
    virtual PowerTrace trace() const = 0;
};

// Opens the source named by spec (forms above); throws trn::Error naming the spec and why (not
// found, with what was found; library missing; counter unsupported).
std::unique_ptr<PowerSampler> make_power_sampler(const std::string& spec, const SamplerOptions& options);

// One line per source that make_power_sampler would accept, plus one line saying why NVML is not
// available when it is not (no error: listing is a survey).
std::vector<std::string> list_power_sources(const SamplerOptions& options);

// The clock poll times are read on. Monotonic cannot step; Realtime is UNIX time and lines up with
// other wall-clock logs and markers.
enum class SampleClock { Monotonic, Realtime };
double clock_seconds(SampleClock clock);

// Polls every period_s for duration_s (the first poll at once) and returns the trace, with
// wall_clock set for SampleClock::Realtime.
PowerTrace sample_for(PowerSampler& sampler, double period_s, double duration_s, SampleClock clock);

}  // namespace trn::energy
TRN_API_END
