// Energy-counter logs (rapl-tools, perf stat), hwmon text records and trnkit's own format.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <regex>
#include <cstdio>
#include <sstream>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {

PowerTrace parse_rapl_tools_csv(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (rapl-tools)";
    OptionReader o(options, parser, {"domain", "max_power_w"});
    const std::string domain = o.text("domain", "pkg");
    const std::vector<std::string> domains = {"pkg", "pp0", "pp1", "dram"};
    const auto it = std::find(domains.begin(), domains.end(), domain);
    if (it == domains.end()) throw Error(parser + ": domain must be pkg, pp0, pp1 or dram");
    const int cw = static_cast<int>(it - domains.begin());
    TraceBuilder b(name, "rapl-tools");
    b.power_source("cpu", o);
    b.trace().quantity = domain + " (RAPL, mean over each interval)";
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().first_interval_start = 0.0;  // elapsed time counts from the meter's start
    for (const auto& l : text::split_lines(input)) {
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != 5) text::fail(name, l.number, "expected 5 fields pkg_W,pp0_W,pp1_W,dram_W,elapsed_s, found " + std::to_string(f.size()));
        const auto w = text::to_number(f[cw]);
        const auto t = text::to_number(f[4]);
        if (!w || !t) text::fail(name, l.number, "fields must be numbers");
        if (!b.trace().t.empty() || *t > 0) b.add(l.number, *t, *w);
        else text::fail(name, l.number, "elapsed time must be > 0");
    }
    return b.finish();
}

double parse_rapl_tools_total_energy(std::string_view input, const std::string& name) {
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (!text::starts_with(s, "Total Energy:")) continue;
        auto rest = text::trim(s.substr(13));
        if (rest.size() < 2 || rest.substr(rest.size() - 2) != " J") text::fail(name, l.number, "expected 'Total Energy: <number> J'");
        const auto j = text::to_number(rest.substr(0, rest.size() - 2));
        if (!j) text::fail(name, l.number, "total energy is not a number");
        return *j;
    }
    throw Error(name + ": no 'Total Energy:' line (not a rapl-tools power.log summary)");
}

// `perf stat -I MS -e power/energy-pkg/[,power/energy-ram/]` with -x SEP (CSV) or perf's own
// aligned text ("     1.001048308              19.63 Joules power/energy-pkg/"). One row per
// event and interval; event= picks one of several, event=sum adds them per interval.
PowerTrace parse_perf_stat(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (perf-stat)";
    OptionReader o(options, parser, {"event", "max_power_w"});
    TraceBuilder b(name, "perf-stat");
    b.power_source("cpu", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().first_interval_start = 0.0;  // -I times count from the start of perf stat
    struct Row { std::size_t line; double t; std::optional<double> j; std::string event; };
    std::vector<Row> rows;
    std::vector<std::string> events;
    // "1,234.56" (thousands separators in perf's text output) -> 1234.56
    auto count_value = [](const std::string& v) -> std::optional<double> {
        if (auto n = text::to_number(v)) return n;
        static const std::regex grouped(R"(^[0-9]{1,3}(,[0-9]{3})+(\.[0-9]+)?$)");
        if (!std::regex_match(v, grouped)) return std::nullopt;
        std::string plain;
        for (char c : v)
            if (c != ',') plain += c;
        return text::to_number(plain);
    };
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (s.empty() || s.front() == '#') continue;
        std::vector<std::string> f;
        for (char sep : {',', ';'}) {
            const auto parts = text::split(s, sep);
            if (parts.size() >= 4 && text::to_number(parts[0])) {
                for (auto p : parts) f.emplace_back(text::trim(p));
                break;
            }
        }
        if (f.empty()) {  // perf's aligned text: time value unit event [...]
            auto tok = text::split_ws(s);
            std::vector<std::string> t2;
            for (std::size_t i = 0; i < tok.size(); ++i) {
                if (tok[i] == "<not" && i + 1 < tok.size()) t2.push_back(std::string(tok[i]) + " " + std::string(tok[i + 1])), ++i;
                else t2.emplace_back(tok[i]);
            }
            f = std::move(t2);
        }
        if (f.size() < 4) text::fail(name, l.number, "expected 'time,value,unit,event,...' (perf stat -x, -I) or 'time value Joules event' (perf stat -I)");
        const auto t = text::to_number(f[0]);
        if (!t) text::fail(name, l.number, "interval time '" + f[0] + "' is not a number");
        std::optional<double> j;
        if (f[1].rfind("<not", 0) == 0) {
            b.drop(l.number, "event " + f[1] + " in this interval");
        } else {
            j = count_value(f[1]);
            if (!j) text::fail(name, l.number, "value '" + f[1] + "' is not a number");
            if (f[2] != "Joules") text::fail(name, l.number, "unit '" + f[2] + "' is not Joules: not an energy event");
        }
        if (std::find(events.begin(), events.end(), f[3]) == events.end()) events.push_back(f[3]);
        rows.push_back({l.number, *t, j, f[3]});
    }
    const std::string want = o.text("event", "");
    auto matches = [](const std::string& event, const std::string& wanted) {
        return event == wanted || event == "power/" + wanted + "/" || event == wanted + "/";
    };
    if (events.size() > 1 && want.empty()) {
        std::string list;
        for (const auto& e : events) list += (list.empty() ? "" : ", ") + e;
        throw Error(parser + ": " + std::to_string(events.size()) + " energy events in the log (" + list +
                    "): pass event=NAME for one or event=sum for their sum; none is picked silently");
    }
    if (!want.empty() && want != "sum" && std::none_of(events.begin(), events.end(), [&](const std::string& e) { return matches(e, want); }))
        throw Error(parser + ": event='" + want + "' is not in the log");
    double prev = 0;
    std::string quantity = want == "sum" ? "sum of " : "";
    if (want == "sum") {
        for (const auto& e : events) quantity += e + (e == events.back() ? "" : "+");
    } else {
        quantity = want.empty() ? (events.empty() ? "" : events.front()) : want;
    }
    for (std::size_t i = 0; i < rows.size();) {
        // the rows of one interval (same time)
        std::size_t k = i;
        double joules = 0;
        std::size_t seen = 0;
        bool missing = false;
        while (k < rows.size() && rows[k].t == rows[i].t) {
            if (want == "sum" || want.empty() || matches(rows[k].event, want)) {
                ++seen;
                if (rows[k].j) joules += *rows[k].j;
                else missing = true;
            }
            ++k;
        }
        const Row& r = rows[i];
        if (!(r.t > prev)) text::fail(name, r.line, "interval end does not come after the previous one");
        if (want == "sum" && seen != events.size())
            text::fail(name, r.line, "interval at " + std::to_string(r.t) + " s lacks one of the " + std::to_string(events.size()) + " events: cannot sum");
        if (seen && !missing) b.add(r.line, r.t, joules / (r.t - prev));
        if (seen) prev = r.t;
        i = k;
    }
    b.trace().quantity = quantity + " (joules per interval / interval)";
    b.trace().resolution_w = 0.01;  // perf prints joules with two decimals
    b.note("perf prints joules rounded to 0.01 J per interval");
    return b.finish();
}

namespace {

// `date` output: "Fr 20. Okt 17:43:31 CEST 2023" (German) or "Tue Jan 26 18:22:31 UTC 2021".
std::optional<double> parse_date_output(std::string_view s) {
    const auto tok = text::split_ws(s);
    if (tok.size() != 6) return std::nullopt;
    static const std::map<std::string, int> months = {
        {"jan", 1}, {"feb", 2}, {"mar", 3}, {"mär", 3}, {"apr", 4}, {"may", 5}, {"mai", 5}, {"jun", 6}, {"jul", 7},
        {"aug", 8}, {"sep", 9}, {"oct", 10}, {"okt", 10}, {"nov", 11}, {"dec", 12}, {"dez", 12}};
    static const std::map<std::string, double> zones = {{"UTC", 0}, {"GMT", 0}, {"CET", 3600}, {"CEST", 7200},
                                                        {"EST", -18000}, {"EDT", -14400}, {"PST", -28800}, {"PDT", -25200}};
    std::string_view day = tok[1], month = tok[2];
    if (!day.empty() && day.back() == '.') day.remove_suffix(1);
    if (!text::to_number(day)) std::swap(day, month);  // English order: weekday month day
    if (!month.empty() && month.back() == '.') month.remove_suffix(1);
    const auto m = months.find(text::lower(month.substr(0, month.size() >= 3 ? 3 : month.size())));
    const auto d = text::to_number(day);
    const auto y = text::to_number(tok[5]);
    const auto z = zones.find(std::string(tok[4]));
    int hh = 0, mm = 0, ss = 0;
    char extra = 0;
    if (m == months.end() || !d || !y || z == zones.end() ||
        std::sscanf(std::string(tok[3]).c_str(), "%2d:%2d:%2d%c", &hh, &mm, &ss, &extra) != 3)
        return std::nullopt;
    if (*d < 1 || *d > 31 || hh > 23 || mm > 59 || ss > 60 || *y < 1970 || *y > 9999) return std::nullopt;
    return text::civil_to_unix(static_cast<int>(*y), m->second, static_cast<int>(*d), hh, mm, ss) - z->second;
}

}  // namespace

PowerTrace parse_hwmon_records(std::string_view input, const std::string& name, const ParseOptions& options) {
    OptionReader o(options, name + " (hwmon-records)", {"channel", "max_power_w"});
    const std::string ch = o.text("channel", "1");
    const std::string curr_key = "curr" + ch + "_input:", volt_key = "in" + ch + "_input:";
    TraceBuilder b(name, "hwmon-records");
    b.power_source("rail", o);
    b.trace().quantity = "in" + ch + "_input (mV) x curr" + ch + "_input (mA)";
    b.trace().wall_clock = true;
    b.trace().resolution_w = 1e-3;
    std::optional<double> t;
    double ma = 0, mv = 0;
    bool has_ma = false, has_mv = false;
    std::size_t record_line = 0;
    auto flush = [&] {
        if (!t) return;
        if (has_ma && has_mv) b.add(record_line, *t, ma * mv * 1e-6);
        else b.drop(record_line, "record without current/voltage values");
        t.reset();
        has_ma = has_mv = false;
    };
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (s.empty() || s.find_first_not_of('=') == std::string_view::npos) continue;
        if (text::starts_with(s, "Timestamp:")) {
            flush();
            t = parse_date_output(text::trim(s.substr(10)));
            if (!t) text::fail(name, l.number, "time stamp is not `date` output (e.g. 'Fr 20. Okt 17:43:31 CEST 2023')");
            record_line = l.number;
        } else if (text::starts_with(s, curr_key) || text::starts_with(s, volt_key)) {
            if (!t) text::fail(name, l.number, "value before the first Timestamp: line");
            const bool is_curr = text::starts_with(s, curr_key);
            const auto rest = text::trim(s.substr(is_curr ? curr_key.size() : volt_key.size()));
            if (rest.empty()) continue;
            const auto v = text::to_number(rest);
            if (!v) text::fail(name, l.number, "value '" + std::string(rest) + "' is not a number");
            (is_curr ? ma : mv) = *v;
            (is_curr ? has_ma : has_mv) = true;
        } else {
            text::fail(name, l.number, "expected 'Timestamp:', '" + curr_key + "' or '" + volt_key + "'");
        }
    }
    flush();
    return b.finish();
}

PowerTrace parse_trnkit_power(std::string_view input, const std::string& name, const ParseOptions& options) {
    OptionReader o(options, name + " (trnkit)", {"source", "max_power_w"});
    const auto lines = text::split_lines(input);
    if (lines.empty() || !text::starts_with(lines[0].text, "# trnkit-power v1")) text::fail(name, 1, "expected '# trnkit-power v1 ...'");
    TraceBuilder b(name, "trnkit");
    b.power_source(o.text("source", "node"), o);
    for (auto tok : text::split_ws(lines[0].text.substr(17))) {
        const auto eq = tok.find('=');
        if (eq == std::string_view::npos) text::fail(name, 1, "header token '" + std::string(tok) + "' is not key=value");
        const std::string key(tok.substr(0, eq)), value(tok.substr(eq + 1));
        if (key == "kind") {
            if (value == "instant") b.trace().kind = SampleKind::Instant;
            else if (value == "interval-mean") b.trace().kind = SampleKind::IntervalMean;
            else text::fail(name, 1, "kind must be instant or interval-mean");
        } else if (key == "quantity") {
            b.trace().quantity = value;
        } else if (key == "format") {
            b.trace().format = value;
        } else if (key == "wall_clock") {
            b.trace().wall_clock = value == "1";
        } else if (key == "resolution_w" || key == "first_interval_start") {
            const auto v = text::to_number(value);
            if (!v) text::fail(name, 1, key + " is not a number");
            if (key == "resolution_w") b.trace().resolution_w = *v;
            else b.trace().first_interval_start = *v;
        }
    }
    std::size_t li = 1;
    while (li < lines.size() && text::starts_with(lines[li].text, "#")) {
        const auto s = text::trim(lines[li].text.substr(1));
        if (text::starts_with(s, "note: ")) b.note(std::string(s.substr(6)));
        else if (text::starts_with(s, "marker: ")) {
            const auto f = text::split_ws(s.substr(8));
            const auto t = f.empty() ? std::nullopt : text::to_number(f[0]);
            if (!t) text::fail(name, lines[li].number, "marker needs a time");
            b.trace().markers.push_back({*t, f.size() > 1 ? std::string(f[1]) : ""});
        }
        ++li;
    }
    if (li >= lines.size() || text::trim(lines[li].text) != "t_s,power_w") text::fail(name, li + 1, "expected the header 't_s,power_w'");
    for (++li; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        const auto t = f.size() == 2 ? text::to_number(f[0]) : std::nullopt;
        const auto w = f.size() == 2 ? text::to_number(f[1]) : std::nullopt;
        if (!t || !w) text::fail(name, l.number, "expected t_s,power_w numbers");
        b.add(l.number, *t, *w);
    }
    return b.finish();
}

std::string format_trnkit_power(const PowerTrace& tr) {
    std::ostringstream os;
    os.precision(17);
    auto clean = [](std::string s) {
        for (char& c : s)
            if (std::isspace(static_cast<unsigned char>(c))) c = '_';
        return s;
    };
    os << "# trnkit-power v1 kind=" << (tr.kind == SampleKind::Instant ? "instant" : "interval-mean")
       << " format=" << clean(tr.format.empty() ? "trnkit" : tr.format) << " quantity=" << clean(tr.quantity.empty() ? "power" : tr.quantity)
       << " wall_clock=" << (tr.wall_clock ? 1 : 0) << " resolution_w=" << tr.resolution_w;
    if (tr.first_interval_start) os << " first_interval_start=" << *tr.first_interval_start;
    os << "\n";
    for (const auto& n : tr.notes) {
        std::string one = n;
        for (char& c : one)
            if (c == '\n' || c == '\r') c = ' ';
        os << "# note: " << one << "\n";
    }
    for (const auto& m : tr.markers) os << "# marker: " << m.t << " " << clean(m.label.empty() ? "-" : m.label) << "\n";
    os << "t_s,power_w\n";
    for (std::size_t i = 0; i < tr.size(); ++i) os << tr.t[i] << "," << tr.w[i] << "\n";
    return os.str();
}

}  // namespace trn::energy
