#pragma once
// One measured run, from a power log and a marker file to per-frame joules: what
// `trnkit energy integrate` computes and writes (JSON for `energy compare`, CSV for people),
// with the provenance a reader needs (input hashes, parser options, alignment, idle baseline).
#include <map>
#include <string>
#include <vector>

#include "trn/energy/align.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

enum class AlignMode {
    SameClock,  // the log's times are on the marker clock (wall clock, or monotonic with --clock mono)
    Offset,     // t_log = t_marker + offset
    Auto,       // align_auto(): offset and drift from the busy/idle pattern
};

struct IntegrateRequest {
    std::string platform;        // label for `compare`; default "<backend>/<kernel>[/<size>]" from the markers
    AlignMode align = AlignMode::SameClock;
    double offset_s = 0;         // AlignMode::Offset
    double search_s = 0;         // AlignMode::Auto: half-width around offset_s (0: anywhere)
    bool insist = false;         // AlignMode::Auto: accept an ambiguous estimate (with a warning) instead of refusing
    bool realtime = true;        // marker clock: CLOCK_REALTIME, else CLOCK_MONOTONIC
    IntegrationOptions integration;
};

struct ReportFrame {
    FrameEnergy energy;
    double write_ms = 0, exec_ms = 0, read_ms = 0;
    double marker_ms = 0;  // frame time measured on the marker clock
};

struct RunReport {
    std::string platform;
    std::string log_path, log_sha256, log_format, log_quantity;
    std::string markers_path, markers_sha256;
    std::map<std::string, std::string> marker_meta, parse_options;
    SamplingReport sampling;
    double resolution_w = 0;
    std::vector<std::string> log_notes;
    std::string rule, clock, align_mode;
    std::size_t min_samples = 0;
    Alignment alignment;  // mapping always set; window fields only for AlignMode::Auto
    ShiftSensitivity shift;
    double idle_w = 0, idle_first_w = 0, idle_last_w = 0;
    std::size_t idle_segments = 0;
    std::vector<std::string> warnings;
    std::vector<ReportFrame> frames;
};

// The whole step on parsed inputs (paths/hashes are left for the caller to fill in). Throws
// trn::Error when automatic alignment is ambiguous (Alignment::ambiguous) and not insisted on.
RunReport integrate_run(const PowerTrace& trace, const MarkerFile& markers, const IntegrateRequest& request);
// Reads and hashes the files, then integrate_run. An empty markers_path takes the frames from the
// log's own start/end markers (markers_from_trace: PMT dumps).
RunReport integrate_files(const std::string& log_path, const std::string& format, const ParseOptions& parse_options,
                          const std::string& markers_path, const IntegrateRequest& request);

std::string run_report_json(const RunReport& report);
std::string run_report_csv(const RunReport& report);
// Reads what run_report_json wrote; throws trn::Error naming `name` and the missing/bad field.
RunReport parse_run_report_json(const std::string& text, const std::string& name);
RunReport read_run_report(const std::string& path);

}  // namespace trn::energy
TRN_API_END
