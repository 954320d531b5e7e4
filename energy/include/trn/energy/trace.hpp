#pragma once
// A power trace as every parser and sampler returns it: times in seconds, power in watts, and
// the hygiene notes (dropped rows, glitches, assumptions) a reader needs to trust the numbers.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

// Plausibility belongs to the source: every parser drops a reading above its source's cap (or
// below minus the cap) as a glitch, counts it in the trace's warnings and says the cap in a note;
// `max_power_w=` sets it. A source that cannot draw negative power (a GPU, a RAPL counter, a
// Jetson rail) refuses a negative reading (file:line); one that can (a bidirectional INA shunt, an
// unknown meter) keeps it with a warning. power_sources() lists them.
struct PowerSource {
    std::string name;         // rail, gpu, cpu, soc, usb, node, rack
    double max_w = 0;         // plausibility cap (W)
    bool can_be_negative = false;
    std::string description;  // "an INA2xx/INA3221 rail", ...
    // The least a working device of this kind draws (W; 0: no floor). Used to test a unit read
    // from a header: a whole log below it while another unit would fit is refused as a unit error
    // ("Power (mW)" over values that are watts: a computer drawing 4 mW).
    double min_w = 0;
};
const std::vector<PowerSource>& power_sources();
// Throws trn::Error naming the known sources for an unknown name.
const PowerSource& power_source(const std::string& name);

// How one sample relates to time.
enum class SampleKind {
    Instant,       // w[i] is the power at t[i] (INA219, nvidia-smi power.draw.instant, tegrastats)
    IntervalMean,  // w[i] is the mean power over (t[i-1], t[i]] (RAPL, perf stat energy counters)
};

// A point in time named by a log or by `trnkit frames` (PMT "M" lines, frame starts/ends).
struct Marker {
    double t = 0;  // seconds, on the trace's clock
    std::string label;
};

struct PowerTrace {
    std::string source;    // file name, or "sysfs:<path>"
    std::string format;    // "ina219-csv", "ina219-raw", "nvidia-smi", "tegrastats", "pmt", ...
    std::string quantity;  // which reading became the power: "VDD_IN", "bus_V*current_mA", ...
    SampleKind kind = SampleKind::Instant;
    // IntervalMean only: start of the first sample's interval when the log says it (else t[0] is
    // only the end of an interval of unknown start and that first sample is not integrated).
    std::optional<double> first_interval_start;
    bool wall_clock = false;   // t is UNIX time (CLOCK_REALTIME); otherwise relative seconds
    // wall_clock stamps written in the logger's local time without a zone, read as if UTC until
    // a zone is applied (apply_time_zone in time_zone.hpp).
    bool local_time = false;
    std::vector<double> t;     // seconds, strictly increasing
    std::vector<double> w;     // watts, finite
    double resolution_w = 0;   // quantisation step of a power reading (LSB), 0 when unknown
    // Each reading's true time lies within t +- this (s): e.g. an INA219 read some time after its
    // conversion finished. integrate_interval adds its effect to the error bound. 0: exact/unknown.
    double time_uncertainty_s = 0;
    // Standard deviation of each reading's time error (s), when the parser can measure it from
    // the log (ina219-raw: each read's lag behind its conversion, from the read intervals). When
    // > 0 the bound's timing term is a 95 % one (2 sigma of the energy error these errors cause)
    // instead of the worst case from time_uncertainty_s.
    double time_sd_s = 0;
    // Settings the parser used that came from the log itself (calibration in "# key=value"
    // comment lines) merged with the options, as KEY=VALUE: the run report's provenance.
    std::map<std::string, std::string> settings;
    std::vector<std::string> notes;  // hygiene: dropped rows, glitches, gaps, assumed values
    // What a run report must surface as a warning (and the CLI on stderr), not only as a note:
    // readings dropped as physically implausible (above the source's cap), negative readings
    // kept, most rows of a log dropped.
    std::vector<std::string> warnings;
    std::vector<Marker> markers;     // markers embedded in the log

    std::size_t size() const { return t.size(); }
};

// What the sample times say about the logger: real rate, gaps and stale repeats.
struct SamplingReport {
    std::size_t samples = 0;
    double duration_s = 0;
    double median_dt_s = 0;
    double rate_hz = 0;            // 1 / median_dt
    std::size_t gaps = 0;          // intervals longer than 3 x median_dt
    double longest_gap_s = 0;
    std::size_t stale_repeats = 0;  // consecutive identical power values (a logger re-reading a stale register)
};

SamplingReport describe_sampling(const PowerTrace& trace);

// Throws trn::Error naming the source when the trace cannot be integrated: fewer than two
// samples, times not strictly increasing, or a non-finite value.
void validate_trace(const PowerTrace& trace);

}  // namespace trn::energy
TRN_API_END
