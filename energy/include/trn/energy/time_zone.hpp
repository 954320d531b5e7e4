#pragma once
// Local time stamps to UTC. Many loggers (nvidia-smi, tegrastats, INA219 scripts with ISO dates,
// powerstat) write the logging machine's wall clock without a zone; a log stamped one hour ahead
// of the CLOCK_REALTIME markers then matches no frame. A zone is a fixed UTC offset
// (`--utc-offset +01:00`) or a tz database name (`--timezone Europe/Vilnius`) read from a TZif
// file under a zoneinfo folder passed by value (GCC 12 has no std::chrono::tzdb).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trn/energy/parsers.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

class TimeZone {
public:
    // "+01:00", "-0530", "+2", "UTC", "Z"; throws trn::Error naming `option` otherwise.
    static TimeZone fixed(std::string_view offset, const std::string& option = "--utc-offset");
    // A tz database name ("Europe/Vilnius"); throws when the name is not plain or no TZif file.
    static TimeZone named(const std::string& name, const std::string& zoneinfo_dir = "/usr/share/zoneinfo");

    const std::string& name() const { return name_; }
    // Offset (local - UTC, seconds) in force at UTC time t.
    double offset_at_utc(double t) const;
    // UTC seconds of a local wall-clock reading written as if it were UTC. In the hour repeated
    // when clocks go back the earlier reading is taken; *ambiguous is set then.
    double local_to_utc(double local_as_utc, bool* ambiguous = nullptr) const;

private:
    std::string name_;
    std::vector<double> transitions_;  // UTC seconds, increasing
    std::vector<double> offsets_;      // offsets_[0] before transitions_[0], offsets_[i+1] from transitions_[i]
    double last_valid_utc_ = 1e300;    // beyond this the table has no data (a rule string we do not evaluate)
};

// The zone named by the parse options "timezone" / "utc_offset" (at most one), or none.
// Both keys are taken out of `options` so parsers never see them.
std::optional<TimeZone> take_time_zone(ParseOptions& options);

// Moves a trace whose stamps are local wall-clock time (PowerTrace::local_time) to UTC: every
// sample, marker and first_interval_start, with a note. Throws when the trace carries no local
// stamps (a zone given for a relative or zone-stamped log would shift it wrongly).
void apply_time_zone(PowerTrace& trace, const TimeZone& zone);

}  // namespace trn::energy
TRN_API_END
