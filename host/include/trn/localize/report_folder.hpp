#pragma once
// The report of a localization run in one folder, one path for every front end (`trnkit demo`,
// `trnkit localize`, Python's localize): the output folder claimed, the per-step CSV and
// summary.json written (with the fields every run records, from the result's RunInfo), the summary
// printed and the plots drawn. A caller adds only what is its own.
#include <map>
#include <ostream>
#include <string>

#include "trn/localize/localization.hpp"
#include "trn/localize/report.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

struct ReportOptions {
    std::string owner = "localize";   // the output folder's owner (io::open_output_folder): "demo", "localize" ...
    std::string folder_name = "folder";  // how errors about the folder name it (the CLI: "--out")
    bool force = false;               // write into a non-empty folder that is not an earlier output of `owner`
    bool plots = true;                // gnuplot's trajectory.png and error.png
    std::string plot_title;
    std::string odometry = "recorded";           // summary.json's "odometry" unless the run used visual odometry
    std::map<std::string, std::string> strings;  // the caller's own summary.json fields
    std::map<std::string, double> numbers;       // NaN: not given, left out of summary.json
    std::string after_summary;                   // printed after the summary (e.g. the final lat/lon)
    std::map<std::string, std::string> files;    // the caller's own files: plain name in the folder -> contents
    ReferenceTrack reference;                    // drawn on the trajectory plot (camera GPS), per result row
};

// Writes localization.csv, summary.json and (with plots) the plots of `result` over `map` into
// `folder`, and prints the summary and the paths to `os`.
void write_localization_report(const LocalizationResult& result, const std::string& folder, GrayView map, double metres_per_pixel,
                               const ReportOptions& options, std::ostream& os);

}  // namespace trn::localize
TRN_API_END
