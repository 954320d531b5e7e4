#pragma once
// Per-run energy summaries: logs that hold one total per run, not a power trace (CodeCarbon's
// emissions.csv). They are read as runs and their joules, never integrated as a trace: between
// two runs nothing was measured, and an interpolation across the gap would invent the power
// there. Runs of different machines are listed per machine and never added up.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trn/energy/parsers.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct RunSummary {
    std::size_t line = 0;         // the row in the file
    std::string run_id, project;  // as logged (may be empty)
    std::string machine;          // the hardware columns that tell machines apart, joined
    std::string timestamp;        // as logged: when the row was written (the run's end)
    std::optional<double> end_s;  // that stamp in UNIX seconds (local time read as UTC unless it carries a zone)
    double duration_s = 0;
    double energy_j = 0;          // the run's total (energy_consumed, kWh -> J)
    std::optional<double> cpu_j, gpu_j, ram_j;  // its parts where logged
    double mean_w() const { return duration_s > 0 ? energy_j / duration_s : 0; }
};

struct RunSummaries {
    std::string source, format;         // file name, "codecarbon"
    std::vector<RunSummary> runs;       // in file order
    std::vector<std::string> machines;  // distinct machine keys, in order of first appearance
    std::vector<std::string> notes;
    // Joules of the runs of one machine (the only total there is: machines are not summed).
    double machine_energy_j(const std::string& machine) const;
};

// CodeCarbon emissions.csv (header with timestamp, run_id, duration, energy_consumed, ... and
// codecarbon_version). Options: none yet (an unknown key is refused). Throws trn::Error naming
// file:line for an unreadable row, a negative or non-finite energy or duration.
RunSummaries parse_codecarbon_runs(std::string_view text, const std::string& name, const ParseOptions& options = {});
// Reads a file through the checked open path; the format is recognised (only CodeCarbon so far).
RunSummaries read_run_summaries(const std::string& path, const ParseOptions& options = {});
// True when the text's header is a CodeCarbon emissions.csv header.
bool looks_like_codecarbon(std::string_view text);
// The runs as a table (one line per run, then per-machine totals), for `trnkit energy runs`.
std::string format_run_summaries(const RunSummaries& runs);

}  // namespace trn::energy
TRN_API_END
