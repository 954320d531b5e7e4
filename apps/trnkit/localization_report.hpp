#pragma once
// The report of a localization run, one path for `trnkit demo` and `trnkit localize`: the output
// folder claimed, the per-step CSV and summary.json written (with the fields both commands record),
// the summary printed and the plots drawn. Each command adds only what is its own.
#include <map>
#include <ostream>
#include <string>

#include "trn/backend.hpp"
#include "trn/filter/localization.hpp"
#include "trn/filter/particle_filter.hpp"

namespace trn::cli {

struct LocalizationReport {
    std::string command;  // "demo" / "localize": owner of the output folder
    std::string out;      // output folder (already checked with io::check_output_folder)
    bool force = false, plots = true;
    std::string plot_title;
    double sparse = 1;            // share of template pixels scored (1 = dense)
    std::uint64_t seed = 1;
    double filter_rate_hz = 0;
    int template_width = 0;
    std::map<std::string, std::string> strings;  // the command's own summary.json fields
    std::map<std::string, double> numbers;       // NaN: not given, left out of summary.json
    std::string after_summary;                   // printed after the summary (e.g. the final lat/lon)
};

// Writes and prints the report of `result`, scored on `backend` with `cfg`, over `map`.
void report_localization(const filter::LocalizationResult& result, const Backend& backend, const filter::FilterConfig& cfg,
                         GrayView map, double metres_per_pixel, const LocalizationReport& report, std::ostream& os);

}  // namespace trn::cli
