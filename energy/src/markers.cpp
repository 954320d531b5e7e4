#include "trn/energy/markers.hpp"

#include <charconv>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "text_input.hpp"

namespace trn::energy {

namespace {
constexpr std::string_view kHeader = "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms";

bool to_int(std::string_view s, std::int64_t& out) {
    s = text::trim(s);
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && !s.empty();
}
}  // namespace

MarkerFile parse_markers(std::string_view input, const std::string& name) {
    const auto lines = text::split_lines(input);
    if (lines.empty() || !text::starts_with(lines[0].text, "# trnkit-frames v1")) text::fail(name, 1, "expected '# trnkit-frames v1 ...' (a file written by trnkit frames)");
    MarkerFile m;
    for (auto tok : text::split_ws(lines[0].text.substr(18))) {
        const auto eq = tok.find('=');
        if (eq == std::string_view::npos) text::fail(name, 1, "header token '" + std::string(tok) + "' is not key=value");
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
