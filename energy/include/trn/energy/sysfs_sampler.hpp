#pragma once
// Live power sampling from Linux sysfs into a PowerTrace (written with format_trnkit_power, so
// every other step reads it like any log):
//  - hwmon ina2xx (power1_input in uW, else in1_input mV x curr1_input mA) and ina3221
//    (per channel N: inN_input mV x currN_input mA) -> instant watts;
//  - RAPL powercap zones (energy_uj counter, wrapping at max_energy_range_uj) -> interval-mean
//    watts between polls.
// The sysfs root is a parameter, so tests build a fake tree in a temp dir.
#include <string>
#include <vector>

#include "trn/energy/power_sampler.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct SysfsSource {
    std::string kind;     // "hwmon" or "rapl"
    std::string dir;      // hwmonN or powercap zone folder
    std::string name;     // chip name (ina219, ina3221) or zone name (package-0, dram)
    int channel = 1;      // hwmon channel
    std::string describe() const;  // "hwmon:ina3221:2 (/sys/class/hwmon/hwmon3)"
};

// Every power source under root/class/hwmon (ina2xx-style chips: any with currN_input and inN_input
// or power1_input) and root/class/powercap (zones with energy_uj).
std::vector<SysfsSource> list_sysfs_sources(const std::string& root = "/sys");
// "hwmon:NAME[:CHANNEL]" or "rapl:NAME" (NAME: the chip/zone name or its folder name).
SysfsSource find_sysfs_source(const std::string& spec, const std::string& root = "/sys");

class SysfsSampler final : public PowerSampler {
public:
    explicit SysfsSampler(SysfsSource source);
    std::string describe() const override { return source_.describe(); }
    // Reads the source once at time t_s (seconds, strictly increasing); throws trn::Error naming
    // the file when a read fails or a value is not a number.
    void poll(double t_s) override;
    // wall_clock is true (poll times on CLOCK_REALTIME) unless the caller says otherwise; counter
    // wraps are noted.
    PowerTrace trace() const override;
    std::size_t wraps() const { return wraps_; }

private:
    SysfsSource source_;
    PowerTrace trace_;
    bool have_counter_ = false;
    double last_t_ = 0;
    unsigned long long last_uj_ = 0, range_uj_ = 0;
    std::size_t wraps_ = 0;
};

// Polls every period_s for duration_s on CLOCK_REALTIME (UNIX seconds, so markers from
// `trnkit frames` line up on the same clock): sample_for() with SampleClock::Realtime.
PowerTrace sample_sysfs(const SysfsSource& source, double period_s, double duration_s);

}  // namespace trn::energy
TRN_API_END
