// `trnkit energy formats`: the power-log formats, their columns, units, an example line and
// options (the parsers' own catalog, trn/energy/format_catalog.hpp).
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "trn/energy/format_catalog.hpp"

namespace trn::cli {

void add_energy_formats_command(CLI::App* energy) {
    auto* c = energy->add_subcommand("formats", "List the power-log formats: columns, units, an example line and options of each");
    c->callback([] { std::cout << energy::format_catalog_text(); });
}

// --timezone / --utc-offset for a command reading a power log: they become the parser options
// timezone= / utc_offset= (applied by parse_power_log to logs stamped in local time).
void add_log_time_zone_options(CLI::App* c, std::vector<std::string>* opts) {
    c->add_option_function<std::string>("--timezone", [opts](const std::string& v) { opts->push_back("timezone=" + v); },
                                        "The log's time stamps are local time in this tz zone (e.g. Europe/Vilnius)");
    c->add_option_function<std::string>("--utc-offset", [opts](const std::string& v) { opts->push_back("utc_offset=" + v); },
                                        "The log's time stamps are local time at this UTC offset (+HH:MM)");
}

}  // namespace trn::cli
