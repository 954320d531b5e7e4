#pragma once
// The frame marker file written by `trnkit frames`: one row per sync burst, idle gap and frame,
// with start/end on CLOCK_MONOTONIC and CLOCK_REALTIME (ns) and the write/exec/read phase times.
//
//   # trnkit-frames v1 key=value ...
//   kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms
//   sync,0,...   idle,0,...   frame,0,...
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct FrameMarker {
    std::string kind;  // "sync", "idle" or "frame"
    int id = 0;
    std::int64_t mono_start_ns = 0, mono_end_ns = 0, real_start_ns = 0, real_end_ns = 0;
    double write_ms = 0, exec_ms = 0, read_ms = 0;
};

struct MarkerFile {
    std::map<std::string, std::string> meta;  // from the first line: backend, kernel, size, ...
    std::vector<FrameMarker> rows;
};

// Reads either format: the full one above, or the minimal one below (told apart by the first
// line that is not a # comment). Throws trn::Error "name:line: why".
MarkerFile parse_markers(std::string_view text, const std::string& name);
MarkerFile read_markers(const std::string& path);
std::string format_markers(const MarkerFile& markers);

// The minimal marker format, for other tools (one clock, one row per frame):
//   # optional comment lines
//   frame,start_s,end_s
//   0,1733935225.009,1733935225.041
// start_s/end_s are seconds on the power log's own clock (UNIX seconds for wall-clock logs such
// as `energy sample`, nvidia-smi or PMT; the log's relative seconds otherwise), so `integrate`
// needs no --clock; --offset and --align still apply. Frame ids are whole numbers, unique; rows
// are in time order and do not overlap. Parsed into a MarkerFile with meta format=minimal,
// clock=log and both clocks set to the same nanoseconds.
inline constexpr std::string_view kMinimalMarkerHeader = "frame,start_s,end_s";
// Writes the frame rows of `markers` on CLOCK_REALTIME (realtime) or CLOCK_MONOTONIC seconds.
std::string format_minimal_markers(const MarkerFile& markers, bool realtime = true);
// True when meta says the times are already on the log's clock (minimal format, log markers).
bool on_log_clock(const MarkerFile& markers);

// A log's own start/end markers (PMT "M <t> \"start\"" lines) as frames on the log's clock
// (meta format=log-markers, clock=log); throws trn::Error naming the log when it has none or they
// do not pair.
MarkerFile markers_from_trace(const PowerTrace& trace);

// An interval on the power trace's clock.
struct TimedInterval {
    std::string kind;
    int id = 0;
    double start = 0, end = 0;
};

// Which marker clock to read and how it maps onto the trace: t_trace = t + offset + drift*(t - ref).
struct ClockMapping {
    bool realtime = true;  // CLOCK_REALTIME (UNIX time); false: CLOCK_MONOTONIC
    double offset_s = 0;
    double drift = 0;      // seconds per second
    double ref_s = 0;      // marker time at which drift is zero
    double map(double t) const { return t + offset_s + drift * (t - ref_s); }
};
std::vector<TimedInterval> marker_intervals(const MarkerFile& markers, const ClockMapping& mapping);

// PMT-style start/end marker pairs -> frame intervals (ids in order); throws on unpaired ones.
std::vector<TimedInterval> intervals_from_trace_markers(const PowerTrace& trace);

}  // namespace trn::energy
TRN_API_END
