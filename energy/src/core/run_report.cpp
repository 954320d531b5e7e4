#include "trn/energy/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>
#include <utility>

#include "sha256.hpp"
#include "text_input.hpp"
#include "trn/energy/label_check.hpp"
#include "trn/io/input_file.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/error.hpp"
#include "trn/io/provenance.hpp"

namespace trn::energy {
namespace {

using nlohmann::json;

std::string default_platform(const MarkerFile& m) {
    auto get = [&](const char* k) {
        const auto it = m.meta.find(k);
        return it == m.meta.end() ? std::string() : it->second;
    };
    std::string p = get("backend").empty() ? "run" : get("backend");
    if (!get("kernel").empty()) p += "/" + get("kernel");
    if (!get("size").empty() && get("kernel") == "sobel") p += "/" + get("size");
    if (!get("particles").empty() && get("kernel") == "ncc") p += "/" + get("particles");
    return p;
}

// JSON has no NaN: a non-finite number would be a bug upstream, so refuse to write it.
double finite(double v, const char* what) {
    if (!std::isfinite(v)) throw Error(std::string("run report: ") + what + " is not finite");
    return v;
}

// A count or id from a report: nlohmann's get<int>() on 1e300 or -1.5 is a float-to-int cast
// with undefined behaviour, so anything but a whole number in the type's range is refused here.
template <class Int>
Int whole_number(const json& object, const char* key, const std::string& name) {
    const json& v = object.at(key);
    if (v.is_number_unsigned() && std::in_range<Int>(v.get<std::uint64_t>())) return static_cast<Int>(v.get<std::uint64_t>());
    if (v.is_number_integer() && !v.is_number_unsigned() && std::in_range<Int>(v.get<std::int64_t>())) return static_cast<Int>(v.get<std::int64_t>());
    throw Error(name + ": run report field \"" + key + "\" must be a whole number" + (std::is_signed_v<Int> ? "" : " >= 0") + " (got " +
                io::json_line(v).substr(0, 40) + ")");
}

// No frame inside the log is never a result: say why. On one clock, a log that would hold every
// frame if moved by a whole number of quarter hours is stamped in local time (the classic: a log
// one hour ahead of UTC markers).
void refuse_no_frame_inside(const PowerTrace& trace, const RunEnergy& run, AlignMode mode) {
    if (run.frames.empty() || run.usable() > 0) return;
    for (const auto& f : run.frames)
        if (f.flag != "not covered by the trace") return;  // covered but too few samples: flagged frames tell that
    double fs = run.frames.front().start, fe = run.frames.front().end;
    for (const auto& f : run.frames) fs = std::min(fs, f.start), fe = std::max(fe, f.end);
    const double tb = trace.first_interval_start.value_or(trace.t.front()), te = trace.t.back();
    char span[200];
    std::snprintf(span, sizeof span, "the log covers %.3f..%.3f s, the %zu frame(s) %.3f..%.3f s", tb, te, run.frames.size(), fs, fe);
    if (mode == AlignMode::SameClock && trace.wall_clock)
        for (int k = 1; k <= 56; ++k)
            for (int sign : {1, -1}) {
                const double shift = sign * k * 900.0;
                if (fs + shift >= tb && fe + shift <= te) {
                    char why[400];
                    const int minutes = k * 15;
                    std::snprintf(why, sizeof why,
                                  "%s: none of the frames lies inside the log (%s), but all would if the log's stamps were read %d h %02d min %s: "
                                  "they look like local time; pass `utc_offset` %c%02d:%02d (or `timezone` NAME)",
                                  trace.source.c_str(), span, minutes / 60, minutes % 60, sign > 0 ? "earlier" : "later", sign > 0 ? '+' : '-',
                                  minutes / 60, minutes % 60);
                    throw Error(why);
                }
            }
    throw Error(trace.source + ": none of the frames lies inside the log (" + span +
                "): another run's log, a wrong `offset`, or a clock mismatch (`clock`, `align` auto)");
}

}  // namespace

RunReport integrate_run(const PowerTrace& trace, const MarkerFile& markers, const IntegrateRequest& q) {
    validate_trace(trace);
    if (!q.platform.empty()) check_label(q.platform, "platform");
    RunReport r;
    r.platform = q.platform.empty() ? default_platform(markers) : q.platform;
    r.log_format = trace.format, r.log_quantity = trace.quantity, r.log_notes = trace.notes;
    r.sampling = describe_sampling(trace);
    r.resolution_w = trace.resolution_w;
    r.parse_options = trace.settings;  // calibration read from the log; integrate_files adds the options given
    r.marker_meta = markers.meta;
    r.rule = q.integration.rule == Rule::Hold ? "hold" : "trapezoid";
    // Minimal-format and log-embedded markers are already on the log's clock (markers.hpp).
    const bool log_clock = on_log_clock(markers);
    r.clock = log_clock ? "log" : q.realtime ? "realtime" : "monotonic";
    r.min_samples = q.integration.min_samples;
    ClockMapping mapping;
    mapping.realtime = q.realtime;
    switch (q.align) {
        case AlignMode::SameClock:
            r.align_mode = "same-clock";
            if (q.realtime && !trace.wall_clock && !log_clock)
                throw Error(trace.source + ": its times are relative (not UNIX time), so they cannot be matched to CLOCK_REALTIME markers: give an offset or use automatic alignment");
            break;
        case AlignMode::Offset:
            r.align_mode = "offset";
            mapping.offset_s = q.offset_s;
            break;
        case AlignMode::Auto: {
            r.align_mode = "auto";
            AlignOptions ao;
            ao.realtime = q.realtime, ao.guess_s = q.offset_s, ao.search_s = q.search_s;
            r.alignment = align_auto(trace, markers, ao);
            if (r.alignment.ambiguous && !q.insist)
                throw Error(trace.source + ": automatic alignment is ambiguous (" + r.alignment.confidence +
                            "): narrow the search with `offset`/`search`, record a sync pattern (trnkit frames `sync_unit_ms`), or pass `insist` to accept it");
            mapping = r.alignment.mapping;
            break;
        }
    }
    r.alignment.mapping = mapping;
    const RunEnergy run = integrate_frames(trace, marker_intervals(markers, mapping), q.integration);
    refuse_no_frame_inside(trace, run, q.align);
    r.shift = shift_sensitivity(trace, markers, mapping, q.integration);
    r.idle_w = run.idle_w, r.idle_first_w = run.idle_first_w, r.idle_last_w = run.idle_last_w, r.idle_segments = run.idle_segments;
    r.warnings = trace.warnings;  // implausible readings dropped by the parser
    if (r.alignment.ambiguous) r.warnings.push_back("AMBIGUOUS automatic alignment accepted with `insist`: " + r.alignment.confidence);
    r.warnings.insert(r.warnings.end(), run.warnings.begin(), run.warnings.end());
    std::map<int, const FrameMarker*> by_id;
    for (const auto& m : markers.rows)
        if (m.kind == "frame") by_id[m.id] = &m;
    for (const auto& f : run.frames) {
        ReportFrame rf;
        rf.energy = f;
        if (const auto it = by_id.find(f.id); it != by_id.end()) {
            const FrameMarker& m = *it->second;
            rf.write_ms = m.write_ms, rf.exec_ms = m.exec_ms, rf.read_ms = m.read_ms;
            rf.marker_ms = ((q.realtime ? m.real_end_ns - m.real_start_ns : m.mono_end_ns - m.mono_start_ns)) * 1e-6;
        }
        r.frames.push_back(rf);
    }
    return r;
}

RunReport integrate_files(const std::string& log_path, const std::string& format, const ParseOptions& opts, const std::string& markers_path,
                          const IntegrateRequest& q) {
    // No marker file: the log's own start/end markers (PMT dumps) are the frames.
    const std::string log_text = text::read_file(log_path);
    const std::string marker_text = markers_path.empty() ? std::string() : text::read_file(markers_path, text::kMaxSmallInputBytes);
    const PowerTrace trace = parse_power_log(log_text, log_path, format, opts);
    const MarkerFile markers = markers_path.empty() ? markers_from_trace(trace) : parse_markers(marker_text, markers_path);
    RunReport r = integrate_run(trace, markers, q);
    r.log_path = log_path, r.markers_path = markers_path.empty() ? log_path + " (its own start/end markers)" : markers_path;
    r.log_sha256 = sha256_hex(log_text), r.markers_sha256 = sha256_hex(markers_path.empty() ? log_text : marker_text);
    // Provenance: the options given, and the settings the parser read from the log itself
    // (an INA219 log's calibration comments); an option given overrides the log, as in the parser.
    for (const auto& [k, v] : opts) r.parse_options[k] = v;
    return r;
}

std::string run_report_json(const RunReport& r) {
    json j;
    j["trnkit_energy_run"] = 1;
    io::add_provenance(j);
    j["platform"] = r.platform;
    j["inputs"]["log"] = {{"path", r.log_path}, {"sha256", r.log_sha256}, {"format", r.log_format}, {"quantity", r.log_quantity},
                          {"samples", r.sampling.samples}, {"rate_hz", r.sampling.rate_hz}, {"gaps", r.sampling.gaps},
                          {"resolution_w", r.resolution_w}, {"notes", r.log_notes}, {"parse_options", r.parse_options}};
    j["inputs"]["markers"] = {{"path", r.markers_path}, {"sha256", r.markers_sha256}, {"meta", r.marker_meta}};
    j["config"] = {{"rule", r.rule}, {"clock", r.clock}, {"align", r.align_mode}, {"min_samples", r.min_samples}};
    const auto& a = r.alignment;
    j["alignment"] = {{"offset_s", finite(a.mapping.offset_s, "offset")}, {"drift", finite(a.mapping.drift, "drift")}, {"ref_s", a.mapping.ref_s},
                      {"residual_s", a.residual_s}, {"contrast_w", a.contrast_w}, {"window_time_s", a.window_time_s},
                      {"window_offset_s", a.window_offset_s}, {"shift_dt_s", r.shift.dt_s}, {"shift_minus_relative", r.shift.relative_minus},
                      {"shift_plus_relative", r.shift.relative_plus}, {"second_offset_s", a.second_offset_s},
                      {"second_contrast_w", a.second_contrast_w}, {"candidate_ratio", a.candidate_ratio}, {"has_sync", a.has_sync},
                      {"sync_contrast_w", a.sync_contrast_w}, {"sync_ratio", a.sync_ratio}, {"ambiguous", a.ambiguous},
                      {"confidence", a.confidence}};
    j["idle"] = {{"w", r.idle_w}, {"first_w", r.idle_first_w}, {"last_w", r.idle_last_w}, {"segments", r.idle_segments}};
    j["warnings"] = r.warnings;
    json frames = json::array();
    for (const auto& f : r.frames) {
        const auto& e = f.energy;
        frames.push_back({{"id", e.id}, {"start_s", e.start}, {"end_s", e.end}, {"gross_j", finite(e.gross_j, "gross energy")},
                          {"net_j", finite(e.net_j, "net energy")}, {"error_j", finite(e.error_j, "error bound")}, {"samples", e.samples},
                          {"flag", e.flag}, {"marker_ms", f.marker_ms}, {"write_ms", f.write_ms}, {"exec_ms", f.exec_ms}, {"read_ms", f.read_ms}});
    }
    j["frames"] = frames;
    return io::json_text(j, 1);  // outside text (log and marker paths, notes) made valid UTF-8 first
}

std::string run_report_csv(const RunReport& r) {
    std::ostringstream os;
    os << "id,start_s,end_s,gross_j,net_j,error_j,samples,flag,marker_ms,write_ms,exec_ms,read_ms\n";
    char buf[512];
    for (const auto& f : r.frames) {
        const auto& e = f.energy;
        std::snprintf(buf, sizeof buf, "%d,%.9f,%.9f,%.9g,%.9g,%.3g,%zu,\"%s\",%.6f,%.6f,%.6f,%.6f\n", e.id, e.start, e.end, e.gross_j, e.net_j, e.error_j,
                      e.samples, e.flag.c_str(), f.marker_ms, f.write_ms, f.exec_ms, f.read_ms);
        os << buf;
    }
    return os.str();
}

RunReport parse_run_report_json(const std::string& text, const std::string& name) {
    json j;
    io::check_json_depth(text, name);  // a 100000-deep [[...]] would overflow the stack in dump()
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        throw Error(name + ": not JSON (" + io::quote_input(e.what(), 200) + ")");
    }
    RunReport r;
    try {
        if (!j.is_object() || !j.contains("trnkit_energy_run") || j["trnkit_energy_run"] != 1) throw Error(name + ": not a run report (expected \"trnkit_energy_run\": 1, written by trnkit energy integrate)");
        r.platform = j.at("platform").get<std::string>();
        const auto& log = j.at("inputs").at("log");
        r.log_path = log.at("path"), r.log_sha256 = log.at("sha256"), r.log_format = log.at("format"), r.log_quantity = log.at("quantity");
        r.sampling.samples = whole_number<std::size_t>(log, "samples", name), r.sampling.rate_hz = log.at("rate_hz"), r.resolution_w = log.at("resolution_w");
        r.log_notes = log.at("notes").get<std::vector<std::string>>();
        r.parse_options = log.at("parse_options").get<std::map<std::string, std::string>>();
        const auto& mk = j.at("inputs").at("markers");
        r.markers_path = mk.at("path"), r.markers_sha256 = mk.at("sha256");
        r.marker_meta = mk.at("meta").get<std::map<std::string, std::string>>();
        const auto& c = j.at("config");
        r.rule = c.at("rule"), r.clock = c.at("clock"), r.align_mode = c.at("align"), r.min_samples = whole_number<std::size_t>(c, "min_samples", name);
        const auto& a = j.at("alignment");
        r.alignment.mapping.offset_s = a.at("offset_s"), r.alignment.mapping.drift = a.at("drift"), r.alignment.mapping.ref_s = a.at("ref_s");
        r.alignment.residual_s = a.at("residual_s"), r.alignment.contrast_w = a.at("contrast_w");
        r.shift.dt_s = a.at("shift_dt_s"), r.shift.relative_minus = a.at("shift_minus_relative"), r.shift.relative_plus = a.at("shift_plus_relative");
        // Confidence fields came later: reports without them read as "not recorded".
        r.alignment.second_offset_s = a.value("second_offset_s", 0.0), r.alignment.second_contrast_w = a.value("second_contrast_w", 0.0);
        r.alignment.candidate_ratio = a.value("candidate_ratio", 0.0), r.alignment.has_sync = a.value("has_sync", false);
        r.alignment.sync_contrast_w = a.value("sync_contrast_w", 0.0), r.alignment.sync_ratio = a.value("sync_ratio", 0.0);
        r.alignment.ambiguous = a.value("ambiguous", false), r.alignment.confidence = a.value("confidence", std::string());
        const auto& idle = j.at("idle");
        r.idle_w = idle.at("w"), r.idle_first_w = idle.at("first_w"), r.idle_last_w = idle.at("last_w"), r.idle_segments = whole_number<std::size_t>(idle, "segments", name);
        r.warnings = j.at("warnings").get<std::vector<std::string>>();
        for (const auto& f : j.at("frames")) {
            ReportFrame rf;
            auto& e = rf.energy;
            e.id = whole_number<int>(f, "id", name), e.start = f.at("start_s"), e.end = f.at("end_s"), e.gross_j = f.at("gross_j"), e.net_j = f.at("net_j");
            e.error_j = f.at("error_j"), e.samples = whole_number<std::size_t>(f, "samples", name), e.flag = f.at("flag");
            rf.marker_ms = f.at("marker_ms"), rf.write_ms = f.at("write_ms"), rf.exec_ms = f.at("exec_ms"), rf.read_ms = f.at("read_ms");
            r.frames.push_back(rf);
        }
    } catch (const json::exception& e) {
        throw Error(name + ": run report field missing or of the wrong type (" + e.what() + ")");
    }
    // A report edited by hand reaches compare's tables and terminal: its label obeys the same rule.
    check_label(r.platform, name + ": platform");
    return r;
}

RunReport read_run_report(const std::string& path) { return parse_run_report_json(text::read_file(path, text::kMaxSmallInputBytes), path); }

}  // namespace trn::energy
