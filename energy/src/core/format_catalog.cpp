#include "trn/energy/format_catalog.hpp"

#include <sstream>

namespace trn::energy {

const std::vector<PowerLogFormat>& power_log_format_catalog() {
    static const std::vector<PowerLogFormat> formats = {
#define TRN_POWER_FORMAT(name, parser, source, columns, units, example, options, quirks) {name, source, columns, units, example, options, quirks},
#include "power_formats.def"
#undef TRN_POWER_FORMAT
    };
    return formats;
}

std::string format_catalog_text() {
    std::ostringstream os;
    os << "Power-log formats (--format NAME, or auto). Every format also takes --timezone NAME / --utc-offset +HH:MM\n"
          "for local time stamps and --opt time_uncertainty_s=S (each stamp's time known to +-S s, added to the\n"
          "error bounds); --opt KEY=VALUE passes the options below. max_power_w=W sets the plausibility cap of any\n"
          "format (readings beyond +-W are dropped and warned; the cap is said in a note).\n";
    for (const auto& f : power_log_format_catalog()) {
        os << "\n" << f.name << ": " << f.source << "\n";
        os << "  columns: " << f.columns << "\n";
        os << "  units:   " << f.units << "\n";
        os << "  example: " << f.example << "\n";
        os << "  options: " << f.options << "\n";
        os << "  quirks:  " << f.quirks << "\n";
    }
    return os.str();
}

}  // namespace trn::energy
