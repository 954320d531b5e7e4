#pragma once
// What `trnkit energy formats` prints: every power-log format the parsers read, with the
// columns they use, the units, an example line and the options (one place, next to the parsers).
#include <string>
#include <vector>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct PowerLogFormat {
    std::string name;     // as --format takes it (power_log_formats())
    std::string source;   // the logger that writes it
    std::string columns;  // what is read from each line
    std::string units;    // of time and power
    std::string example;  // one data line
    std::string options;  // --opt KEY=VALUE it accepts
    std::string quirks;   // what the parser does about the format's known traps
};

// In power_log_formats() order: both come from energy/src/core/power_formats.def.
const std::vector<PowerLogFormat>& power_log_format_catalog();
// The catalog as text for a terminal.
std::string format_catalog_text();

}  // namespace trn::energy
TRN_API_END
