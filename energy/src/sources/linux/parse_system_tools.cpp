// Linux system tools that print power next to other statistics: powerstat (vmstat-like table,
// time of day only) and turbostat (RAPL columns, one summary row per interval).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

// "HH:MM:SS" -> seconds of the day.
std::optional<double> time_of_day(std::string_view s) {
    if (s.size() != 8 || s[2] != ':' || s[5] != ':') return std::nullopt;
    const auto h = text::to_number(s.substr(0, 2)), m = text::to_number(s.substr(3, 2)), sec = text::to_number(s.substr(6, 2));
    if (!h || !m || !sec || *h > 23 || *m > 59 || *sec > 60) return std::nullopt;
    return *h * 3600 + *m * 60 + *sec;
}

int index_of(const std::vector<std::string_view>& tokens, std::string_view name) {
    const auto it = std::find(tokens.begin(), tokens.end(), name);
    return it == tokens.end() ? -1 : static_cast<int>(it - tokens.begin());
}

}  // namespace

PowerTrace parse_powerstat(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (powerstat)";
    OptionReader o(options, parser, {"column", "date", "max_power_w"});
    const std::string column = o.text("column", "Watts");
    // powerstat prints the time of day only; date=YYYY-MM-DD makes the stamps absolute (local time).
    std::optional<double> day0;
    if (const auto d = o.text("date")) {
        day0 = text::parse_datetime(*d + " 00:00:00");
        if (!day0) throw Error(parser + ": option date='" + *d + "' is not YYYY-MM-DD");
    }
    TraceBuilder b(name, "powerstat");
    b.power_source("cpu", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().quantity = column + " (powerstat; RAPL or battery, mean over each sample interval)";
    b.trace().resolution_w = 0.01;
    int cw = -1;
    std::size_t columns = 0;
    double days = 0, last_tod = -1;
    for (const auto& l : text::split_lines(input)) {
        const auto tok = text::split_ws(l.text);
        if (tok.empty()) continue;
        if (cw < 0) {
            if (tok.front() == "Time" && index_of(tok, "Watts") >= 0) {
                cw = index_of(tok, column);
                if (cw < 0) text::fail(name, l.number, "header has no '" + column + "' column");
                columns = tok.size();
            } else {
                b.drop(l.number, "text before the table header");
            }
            continue;
        }
        if (text::starts_with(tok.front(), "--------")) break;  // summary (Average, StdDev, ...) follows
        if (tok.front() == "Time") continue;                      // header repeated
        const auto tod = time_of_day(tok.front());
        if (!tod) text::fail(name, l.number, "expected a row starting with HH:MM:SS, found '" + std::string(tok.front()) + "'");
        if (tok.size() != columns) text::fail(name, l.number, "expected " + std::to_string(columns) + " fields as in the header, found " + std::to_string(tok.size()));
        if (last_tod >= 0 && *tod < last_tod - 43200) days += 1;  // past midnight
        last_tod = *tod;
        const auto w = text::to_number(tok[cw]);
        if (!w) {
            b.drop(l.number, "power not a number ('" + std::string(tok[cw]).substr(0, 20) + "')");
            continue;
        }
        b.add(l.number, (day0 ? *day0 : 0.0) + days * 86400 + *tod, *w);
    }
    if (cw < 0) throw Error(parser + ": no header line 'Time ... Watts'");
    if (day0) {
        b.trace().wall_clock = b.trace().local_time = true;
        b.note("time of day on date= in the logging machine's local time, 1 s resolution; taken as UTC (timezone= / utc_offset= to convert)");
    } else {
        b.note("time of day only (seconds since midnight of the first day, 1 s resolution); pass date=YYYY-MM-DD for absolute time");
    }
    b.note("each reading is the mean power over the interval ending at its time; the first reading's interval start is unknown and it is not integrated");
    return b.finish();
}

PowerTrace parse_turbostat(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (turbostat)";
    OptionReader o(options, parser, {"column", "interval_s", "max_power_w"});
    const std::string column = o.text("column", "PkgWatt");
    const auto interval = o.number("interval_s");
    if (interval && !(*interval > 0)) throw Error(parser + ": option interval_s must be > 0");
    TraceBuilder b(name, "turbostat");
    b.power_source("cpu", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().quantity = column + " (turbostat, RAPL energy over each interval)";
    std::vector<std::string_view> header;
    int cw = -1, ct = -1, ccpu = -1, ccore = -1;
    struct Row { std::size_t line; double t; double w; };
    std::vector<Row> rows;
    std::vector<double> seconds;  // "10.003521 sec": the length of a measurement (turbostat CMD)
    for (const auto& l : text::split_lines(input)) {
        const auto tok = text::split_ws(l.text);
        if (tok.empty()) continue;
        if (tok.size() == 2 && tok[1] == "sec" && text::to_number(tok[0])) {
            seconds.push_back(*text::to_number(tok[0]));
            continue;
        }
        if (index_of(tok, column) >= 0 && !text::to_number(tok.front())) {  // a header (turbostat repeats it)
            if (!header.empty() && tok != header) text::fail(name, l.number, "header differs from the first one (columns changed mid-log)");
            header = tok;
            cw = index_of(tok, column), ct = index_of(tok, "Time_Of_Day_Seconds"), ccpu = index_of(tok, "CPU"), ccore = index_of(tok, "Core");
            continue;
        }
        if (header.empty()) {
            b.drop(l.number, "text before the first header naming " + column + " (version banner, CPUID/MSR lines)");
            continue;
        }
        // The summary row of an interval has '-' as CPU (or Core); per-CPU rows follow it.
        const int key = ccpu >= 0 ? ccpu : ccore;
        if (key >= 0 && (static_cast<std::size_t>(key) >= tok.size() || tok[key] != "-")) continue;
        if (tok.size() != header.size())
            text::fail(name, l.number, "summary row has " + std::to_string(tok.size()) + " fields, the header " + std::to_string(header.size()));
        const auto w = text::to_number(tok[cw]);
        if (!w) text::fail(name, l.number, column + " '" + std::string(tok[cw]) + "' is not a number");
        double t = 0;
        if (ct >= 0) {
            const auto v = text::to_number(tok[ct]);
            if (!v) text::fail(name, l.number, "Time_Of_Day_Seconds '" + std::string(tok[ct]) + "' is not a number");
            t = *v;
        }
        rows.push_back({l.number, t, *w});
    }
    if (header.empty()) throw Error(parser + ": no header line naming " + column + " (turbostat --show " + column + ",...)");
    if (ct < 0) {
        // Without a time column the interval must come from the file or the option, never a default.
        std::vector<double> ends;
        if (interval) {
            for (std::size_t i = 0; i < rows.size(); ++i) ends.push_back(static_cast<double>(i + 1) * *interval);
            b.note("no Time_Of_Day_Seconds column: rows placed every interval_s");
        } else if (!seconds.empty() && seconds.size() == rows.size()) {
            double sum = 0;
            for (double s : seconds) ends.push_back(sum += s);
            b.note("no Time_Of_Day_Seconds column: each row's interval from turbostat's 'N.NNN sec' line after it");
        } else {
            throw Error(parser + ": no Time_Of_Day_Seconds column and no interval in the log (" + std::to_string(seconds.size()) + " 'sec' line(s) for " +
                        std::to_string(rows.size()) + " row(s)): pass interval_s=SECONDS (turbostat --interval), or log with --show Time_Of_Day_Seconds");
        }
        for (std::size_t i = 0; i < rows.size(); ++i) b.add(rows[i].line, ends[i], rows[i].w);
        b.trace().first_interval_start = 0.0;
    } else {
        for (const auto& r : rows) b.add(r.line, r.t, r.w);
        if (interval) b.trace().first_interval_start = b.trace().t.empty() ? 0.0 : b.trace().t.front() - *interval;
        else b.note("each reading is the mean over the interval ending at its time; the first interval's start is unknown (pass interval_s= to integrate it)");
    }
    b.trace().resolution_w = 0.01;
    return b.finish();
}

PowerTrace parse_powerjoular(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (powerjoular)";
    OptionReader o(options, parser, {"column", "max_power_w"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    std::vector<std::string> cols;
    for (auto f : text::split(lines[hi].text, ',')) cols.emplace_back(text::trim(f));
    auto col = [&](const std::string& n) {
        for (std::size_t i = 0; i < cols.size(); ++i)
            if (text::lower(cols[i]) == text::lower(n)) return static_cast<int>(i);
        return -1;
    };
    if (col("Date") != 0) text::fail(name, lines[hi].number, "expected the PowerJoular header 'Date,CPU Utilization,...'");
    const std::string column = o.text("column", col("Total Power") >= 0 ? "Total Power" : "CPU Power");
    const int cp = col(column);
    if (cp < 0) text::fail(name, lines[hi].number, "header has no '" + column + "' column");
    TraceBuilder b(name, "powerjoular");
    b.power_source(column == "GPU Power" ? "gpu" : column == "CPU Power" ? "cpu" : "node", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().quantity = column + " (PowerJoular, mean over the second before each stamp)";
    b.trace().wall_clock = b.trace().local_time = true;
    b.trace().resolution_w = 0;
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != cols.size()) text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields as in the header, found " + std::to_string(f.size()));
        const auto t = text::parse_datetime(f[0]);
        if (!t) text::fail(name, l.number, "Date '" + std::string(text::trim(f[0])) + "' is not YYYY-MM-DD HH:MM:SS");
        const auto w = text::to_number(f[cp]);
        if (!w) text::fail(name, l.number, column + " '" + std::string(text::trim(f[cp])) + "' is not a number");
        b.add(l.number, *t, *w);
    }
    if (!b.trace().t.empty()) b.trace().first_interval_start = b.trace().t.front() - 1.0;
    b.note("each row is the mean power over the 1 s cycle ending at its stamp (PowerJoular's period); stamps have 1 s resolution and no time zone, "
           "taken as UTC (timezone= / utc_offset= to convert)");
    return b.finish();
}

}  // namespace trn::energy
