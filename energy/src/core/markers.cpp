#include "trn/energy/markers.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "text_input.hpp"
#include "trn/energy/label_check.hpp"
#include "trn/io/input_file.hpp"

namespace trn::energy {

namespace {
constexpr std::string_view kHeader = "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms";

bool to_int(std::string_view s, std::int64_t& out) {
    s = text::trim(s);
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && !s.empty();
}
}  // namespace

namespace {

std::int64_t seconds_to_ns(double s) { return std::llround(s * 1e9); }

// frame,start_s,end_s rows after `header` (index into lines).
MarkerFile parse_minimal(const std::vector<text::Line>& lines, std::size_t header, const std::string& name) {
    MarkerFile m;
    m.meta = {{"format", "minimal"}, {"clock", "log"}};
    std::map<int, std::size_t> id_line;
    std::size_t previous_line = 0;
    for (std::size_t i = header + 1; i < lines.size(); ++i) {
        const auto& l = lines[i];
        const auto s = text::trim(l.text);
        if (s.empty() || s.front() == '#') continue;
        const auto f = text::split(s, ',');
        if (f.size() != 3) text::fail(name, l.number, "expected 3 fields (frame,start_s,end_s), found " + std::to_string(f.size()));
        std::int64_t id = 0;
        if (!to_int(f[0], id) || id < 0 || id > std::numeric_limits<int>::max()) text::fail(name, l.number, "frame id must be a whole number in [0, 2^31-1]");
        const auto a = text::to_number(f[1]), b = text::to_number(f[2]);
        // 9.2e9 s keeps nanoseconds inside int64 (UNIX time until the year 2262).
        if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b) || std::abs(*a) > 9.2e9 || std::abs(*b) > 9.2e9)
            text::fail(name, l.number, "start_s and end_s must be finite seconds (|t| < 9.2e9)");
        if (*b < *a) text::fail(name, l.number, "end_s comes before start_s");
        FrameMarker r;
        r.kind = "frame", r.id = static_cast<int>(id);
        r.mono_start_ns = r.real_start_ns = seconds_to_ns(*a);
        r.mono_end_ns = r.real_end_ns = seconds_to_ns(*b);
        if (const auto [it, fresh] = id_line.emplace(r.id, l.number); !fresh)
            text::fail(name, l.number, "frame id " + std::to_string(r.id) + " repeats the row at line " + std::to_string(it->second));
        if (!m.rows.empty() && r.real_start_ns < m.rows.back().real_end_ns)
            text::fail(name, l.number, "frame " + std::to_string(r.id) + " starts before frame " + std::to_string(m.rows.back().id) + " (line " +
                                           std::to_string(previous_line) + ") ends: rows overlap or are out of time order");
        previous_line = l.number;
        m.rows.push_back(r);
    }
    if (m.rows.empty()) text::fail(name, lines[header].number, "no frame rows after the header");
    return m;
}

}  // namespace

MarkerFile parse_markers(std::string_view input, const std::string& name) {
    input = io::strip_bom(input);  // a UTF-8 byte order mark (a file saved by a spreadsheet or editor)
    text::check_row_widths(input, name);  // the memory budget before any row is split
    const auto lines = text::split_lines(input);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const auto s = text::trim(lines[i].text);
        if (s.empty() || (s.front() == '#' && !text::starts_with(s, "# trnkit-frames"))) continue;
        if (s == kMinimalMarkerHeader) return parse_minimal(lines, i, name);
        break;
    }
    if (lines.empty() || !text::starts_with(lines[0].text, "# trnkit-frames v1"))
        text::fail(name, 1, "expected '# trnkit-frames v1 ...' (a file written by trnkit frames) or the minimal header '" + std::string(kMinimalMarkerHeader) + "'");
    MarkerFile m;
    for (auto tok : text::split_ws(lines[0].text.substr(18))) {
        const auto eq = tok.find('=');
        if (eq == std::string_view::npos) text::fail(name, 1, "header token '" + io::quote_input(tok) + "' is not key=value");
        // Header values reach reports, plots and the terminal (platform=...): UTF-8, no escape sequences.
        try {
            check_label(tok, "header token");
        } catch (const Error& e) {
            text::fail(name, 1, e.what());
        }
        m.meta[std::string(tok.substr(0, eq))] = std::string(tok.substr(eq + 1));
    }
    if (lines.size() < 2 || text::trim(lines[1].text) != kHeader) text::fail(name, 2, "expected the column header '" + std::string(kHeader) + "'");
    // A repeated id would pair a frame's energy with another frame's phase times, and
    // overlapping rows would count the same joules twice: both are refused, naming both lines.
    std::map<std::pair<std::string, int>, std::size_t> id_line;
    std::size_t previous_line = 0;
    for (std::size_t i = 2; i < lines.size(); ++i) {
        const auto& l = lines[i];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != 9) text::fail(name, l.number, "expected 9 fields, found " + std::to_string(f.size()));
        FrameMarker r;
        r.kind = std::string(text::trim(f[0]));
        if (r.kind != "sync" && r.kind != "idle" && r.kind != "frame") text::fail(name, l.number, "kind must be sync, idle or frame");
        std::int64_t v[5];
        for (int k = 0; k < 5; ++k)
            if (!to_int(f[1 + k], v[k])) text::fail(name, l.number, "field " + std::to_string(k + 2) + " is not an integer");
        if (v[0] < 0 || v[0] > std::numeric_limits<int>::max()) text::fail(name, l.number, "frame id " + std::to_string(v[0]) + " is outside [0, 2^31-1]");
        r.id = static_cast<int>(v[0]);
        r.mono_start_ns = v[1], r.mono_end_ns = v[2], r.real_start_ns = v[3], r.real_end_ns = v[4];
        if (r.mono_end_ns < r.mono_start_ns || r.real_end_ns < r.real_start_ns) text::fail(name, l.number, "end comes before start");
        const auto w = text::to_number(f[6]), e = text::to_number(f[7]), rd = text::to_number(f[8]);
        if (!w || !e || !rd) text::fail(name, l.number, "phase times must be numbers");
        r.write_ms = *w, r.exec_ms = *e, r.read_ms = *rd;
        if (const auto [it, fresh] = id_line.emplace(std::pair{r.kind, r.id}, l.number); !fresh)
            text::fail(name, l.number, r.kind + " id " + std::to_string(r.id) + " repeats the row at line " + std::to_string(it->second));
        if (!m.rows.empty()) {
            const FrameMarker& p = m.rows.back();
            const char* clock = r.mono_start_ns < p.mono_end_ns ? "CLOCK_MONOTONIC" : r.real_start_ns < p.real_end_ns ? "CLOCK_REALTIME" : nullptr;
            if (clock)
                text::fail(name, l.number, r.kind + " " + std::to_string(r.id) + " starts before " + p.kind + " " + std::to_string(p.id) + " (line " +
                                               std::to_string(previous_line) + ") ends on " + clock + ": rows overlap or are out of time order");
        }
        previous_line = l.number;
        m.rows.push_back(r);
    }
    return m;
}

MarkerFile read_markers(const std::string& path) { return parse_markers(text::read_file(path, text::kMaxSmallInputBytes), path); }

std::string format_markers(const MarkerFile& m) {
    std::ostringstream os;
    os << "# trnkit-frames v1";
    for (const auto& [k, v] : m.meta) os << " " << k << "=" << v;
    os << "\n" << kHeader << "\n";
    char buf[64];
    for (const auto& r : m.rows) {
        os << r.kind << "," << r.id << "," << r.mono_start_ns << "," << r.mono_end_ns << "," << r.real_start_ns << "," << r.real_end_ns;
        for (double v : {r.write_ms, r.exec_ms, r.read_ms}) {
            std::snprintf(buf, sizeof buf, ",%.6f", v);
            os << buf;
        }
        os << "\n";
    }
    return os.str();
}

std::string format_minimal_markers(const MarkerFile& m, bool realtime) {
    std::ostringstream os;
    os << "# frame markers; seconds on " << (realtime ? "CLOCK_REALTIME (UNIX time)" : "CLOCK_MONOTONIC") << "\n" << kMinimalMarkerHeader << "\n";
    char buf[96];
    for (const auto& r : m.rows) {
        if (r.kind != "frame") continue;
        const std::int64_t a = realtime ? r.real_start_ns : r.mono_start_ns, b = realtime ? r.real_end_ns : r.mono_end_ns;
        // Whole seconds and nanoseconds printed apart: a double would round UNIX times to ~0.2 us.
        auto secs = [](std::int64_t ns) {
            char s[40];
            const std::int64_t whole = ns >= 0 ? ns / 1000000000 : -((-ns + 999999999) / 1000000000);
            std::snprintf(s, sizeof s, "%lld.%09lld", static_cast<long long>(whole), static_cast<long long>(ns - whole * 1000000000));
            return std::string(s);
        };
        std::snprintf(buf, sizeof buf, "%d,%s,%s\n", r.id, secs(a).c_str(), secs(b).c_str());
        os << buf;
    }
    return os.str();
}

bool on_log_clock(const MarkerFile& m) {
    const auto it = m.meta.find("clock");
    return it != m.meta.end() && it->second == "log";
}

MarkerFile markers_from_trace(const PowerTrace& trace) {
    if (trace.markers.empty()) throw Error(trace.source + ": the log has no start/end markers of its own: give a marker file (--markers)");
    MarkerFile m;
    m.meta = {{"format", "log-markers"}, {"clock", "log"}};
    for (const auto& iv : intervals_from_trace_markers(trace)) {
        FrameMarker r;
        r.kind = "frame", r.id = iv.id;
        r.mono_start_ns = r.real_start_ns = seconds_to_ns(iv.start);
        r.mono_end_ns = r.real_end_ns = seconds_to_ns(iv.end);
        m.rows.push_back(r);
    }
    if (m.rows.empty()) throw Error(trace.source + ": its markers hold no start/end pair: give a marker file (--markers)");
    return m;
}

std::vector<TimedInterval> marker_intervals(const MarkerFile& m, const ClockMapping& c) {
    std::vector<TimedInterval> out;
    for (const auto& r : m.rows) {
        const double s = (c.realtime ? r.real_start_ns : r.mono_start_ns) * 1e-9;
        const double e = (c.realtime ? r.real_end_ns : r.mono_end_ns) * 1e-9;
        out.push_back({r.kind, r.id, c.map(s), c.map(e)});
    }
    return out;
}

std::vector<TimedInterval> intervals_from_trace_markers(const PowerTrace& trace) {
    std::vector<TimedInterval> out;
    bool open = false;
    double start = 0;
    for (const auto& mk : trace.markers) {
        if (mk.label == "start") {
            if (open) throw Error(trace.source + ": marker 'start' at " + std::to_string(mk.t) + " s follows another 'start'");
            open = true, start = mk.t;
        } else if (mk.label == "end") {
            if (!open) throw Error(trace.source + ": marker 'end' at " + std::to_string(mk.t) + " s has no 'start'");
            open = false;
            out.push_back({"frame", static_cast<int>(out.size()), start, mk.t});
        }
    }
    if (open) throw Error(trace.source + ": the last 'start' marker has no 'end'");
    return out;
}

}  // namespace trn::energy
