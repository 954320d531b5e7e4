// likwid-perfctr's timeline mode (`likwid-perfctr -C 0-3 -g ENERGY -t 500ms ./app 2> log`): one
// row per interval, "<group> <count> <threads> <runtime s> <value>...", the values metric-major
// (metric 1 of every hardware thread, then metric 2 ...), each metric over the last interval. The
// header likwid prints on stdout ("# GID|MetricsCount|CpuCount|Total runtime [s]|<metric>|...")
// names the metrics when it is in the file too.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

// Fields of a timeline line: '|' when likwid wrote the header to a terminal, ',' with -O, else spaces.
std::vector<std::string> fields_of(std::string_view line) {
    for (const char sep : {'|', ','})
        if (line.find(sep) != std::string_view::npos) return text::split_fields(line, sep);
    return text::split_fields(line, 0);
}

// The metric names of a "# GID|MetricsCount|CpuCount|Total runtime [s]|..." header line.
std::optional<std::vector<std::string>> metric_header(std::string_view line) {
    const auto s = text::trim(line);
    // Metric names hold spaces ("Power [W]"): a header split by spaces (-o FILE without -O) cannot
    // be read, and the log is read as one without a header.
    if (!text::starts_with(s, "#") || (s.find('|') == std::string_view::npos && s.find(',') == std::string_view::npos)) return std::nullopt;
    auto f = fields_of(text::trim(s.substr(1)));
    if (f.size() < 5 || f[0] != "GID" || (f[1] != "MetricsCount" && f[1] != "EventCount") || f[2] != "CpuCount") return std::nullopt;
    return std::vector<std::string>(f.begin() + 4, f.end());
}

// A data row: group, count, threads and runtime, then count x threads values.
bool timeline_row(const std::vector<std::string>& f) {
    if (f.size() < 5) return false;
    const auto g = text::to_number(f[0]), n = text::to_number(f[1]), c = text::to_number(f[2]), t = text::to_number(f[3]);
    if (!g || !n || !c || !t || *n < 1 || *c < 1 || *n != std::floor(*n) || *c != std::floor(*c)) return false;
    return f.size() == 4 + static_cast<std::size_t>(*n) * static_cast<std::size_t>(*c);
}

}  // namespace

bool looks_like_likwid_timeline(std::string_view input) {
    std::size_t rows = 0;
    for (const auto& l : text::split_lines(input.substr(0, std::min<std::size_t>(input.size(), 65536)))) {
        const auto s = text::trim(l.text);
        if (s.empty()) continue;
        if (metric_header(s)) return true;
        if (s.front() == '#') continue;
        if (!timeline_row(fields_of(s))) return false;
        if (++rows == 3) return true;
    }
    return false;
}

PowerTrace parse_likwid_timeline(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (likwid-timeline)";
    OptionReader o(options, parser, {"metric", "group", "max_power_w"});
    std::vector<std::string> metrics;  // from the header, when the file has it
    TraceBuilder b(name, "likwid-timeline");
    b.power_source("cpu", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().first_interval_start = 0.0;  // runtimes count from likwid-perfctr's start
    std::optional<double> group;
    if (const auto g = o.text("group")) {
        group = text::to_number(*g);
        if (!group) throw Error(parser + ": option group='" + *g + "' is not a group number (the first field of each row)");
    }
    int column = -1;      // index of the chosen metric
    bool joules = false;  // an Energy [J] metric: joules over the interval, divided by its length
    double last_t = 0;
    std::optional<double> first_group;
    std::size_t threads = 0;
    auto choose = [&](std::size_t line, std::size_t count) {
        const auto want = o.text("metric");
        if (want && !metrics.empty()) {
            for (std::size_t i = 0; i < metrics.size(); ++i)
                if (metrics[i] == *want) column = static_cast<int>(i);
            if (column < 0) text::fail(name, line, "no metric '" + *want + "' in the header");
        } else if (want) {
            const auto k = text::to_number(*want);
            if (!k || *k < 1 || *k > static_cast<double>(count) || *k != std::floor(*k))
                throw Error(parser + ": option metric='" + *want + "': without likwid's '# GID|...' header give the metric's number, 1.." +
                            std::to_string(count));
            column = static_cast<int>(*k) - 1;
        } else if (!metrics.empty()) {
            for (std::size_t i = 0; i < metrics.size() && column < 0; ++i)
                if (metrics[i] == "Power [W]") column = static_cast<int>(i);
            if (column < 0) {
                std::string list;
                for (const auto& m : metrics) list += (list.empty() ? "" : ", ") + m;
                text::fail(name, line, "no 'Power [W]' metric (the ENERGY group's); pass metric=NAME, one of: " + list);
            }
        } else {
            text::fail(name, line, "a likwid-perfctr timeline without its '# GID|MetricsCount|...' header: which of its " + std::to_string(count) +
                                       " metrics is power is not said; pass metric=N (its number in the group, e.g. the ENERGY group's Power [W]) "
                                       "or keep likwid's stdout header in the file");
        }
        const std::string label = metrics.empty() ? "metric " + std::to_string(column + 1) : metrics[column];
        joules = label.find("[J]") != std::string::npos;
        if (!metrics.empty() && !joules && label.find("[W]") == std::string::npos)
            text::fail(name, line, "metric '" + label + "' is not a power [W] or energy [J] metric");
        if (metrics.empty()) b.note("metric " + std::to_string(column + 1) + " taken as power in W (metric= says so; the log has no header)");
        b.trace().quantity = label + " summed over " + std::to_string(threads) +
                             " hardware thread(s) (likwid-perfctr timeline; a socket's RAPL metric is counted on one thread of the socket)";
    };
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (s.empty()) continue;
        if (const auto h = metric_header(s)) {
            if (!metrics.empty() && *h != metrics) text::fail(name, l.number, "a second metric header that differs from the first (several groups: pass group=N)");
            metrics = *h;
            continue;
        }
        if (s.front() == '#') continue;  // "# HWThreads|0|1|..." and remarks
        const auto f = fields_of(s);
        if (!timeline_row(f)) text::fail(name, l.number, "expected a timeline row '<group> <count> <threads> <runtime s> <values...>'");
        const double g = *text::to_number(f[0]);
        if (group && g != *group) {
            b.drop(l.number, "a row of another group (group= picks one)");
            continue;
        }
        if (!group && first_group && g != *first_group)
            text::fail(name, l.number, "rows of several groups (likwid switches groups with -T): pass group=N (the first field) to read one");
        first_group = g;
        const auto count = static_cast<std::size_t>(*text::to_number(f[1]));
        const auto cpus = static_cast<std::size_t>(*text::to_number(f[2]));
        if (!metrics.empty() && metrics.size() != count)
            text::fail(name, l.number, "the row has " + std::to_string(count) + " metrics, the header names " + std::to_string(metrics.size()));
        if (column < 0) threads = cpus, choose(l.number, count);
        if (cpus != threads) text::fail(name, l.number, "the row has " + std::to_string(cpus) + " threads, the first had " + std::to_string(threads));
        const double t = *text::to_number(f[3]);
        double sum = 0;
        std::size_t missing = 0;
        for (std::size_t k = 0; k < cpus; ++k) {
            const std::string& v = f[4 + static_cast<std::size_t>(column) * cpus + k];
            if (v == "-" || v == "nan") {
                ++missing;
                continue;
            }
            const auto x = text::to_number(v);
            if (!x) text::fail(name, l.number, "value '" + v + "' is not a number");
            sum += *x;
        }
        if (missing == cpus) {
            b.drop(l.number, "no thread has a value for the metric");
            last_t = t;  // an energy metric's next row covers only its own interval
            continue;
        }
        const double w = joules ? (t > last_t ? sum / (t - last_t) : std::nan("")) : sum;
        if (!std::isfinite(w)) text::fail(name, l.number, "runtime " + f[3] + " s does not advance");
        b.add(l.number, t, w);
        last_t = t;
    }
    if (column < 0) throw Error(parser + ": no timeline rows");
    b.note("interval means (each row's metric is over the interval before its runtime), time relative to likwid-perfctr's start");
    return b.finish();
}

}  // namespace trn::energy
