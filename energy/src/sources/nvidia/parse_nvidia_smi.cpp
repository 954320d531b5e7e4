// nvidia-smi --query-gpu=... --format=csv[,nounits] logs.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

// "power.draw [W]" -> "power.draw"
std::string bare_name(std::string_view column) {
    column = text::trim(column);
    if (const auto b = column.find(" ["); b != std::string_view::npos) column = column.substr(0, b);
    return text::lower(column);
}

// Column names for a --format=csv,noheader log: from columns=..., else guessed from the first
// row (a YYYY/MM/DD time stamp, a whole number before it = index, the one field in W = power).
std::vector<std::string> headerless_columns(std::string_view row, const std::string& name, std::size_t line, const OptionReader& o) {
    std::vector<std::string> cols;
    if (const auto given = o.text("columns")) {
        for (auto f : text::split(*given, ',')) cols.push_back(bare_name(f));
        return cols;
    }
    const auto f = text::split(row, ',');
    int ts = -1;
    std::vector<int> watts, numbers;
    for (std::size_t i = 0; i < f.size(); ++i) {
        const std::string_view v = text::trim(f[i]);
        if (ts < 0 && text::parse_datetime(v)) ts = static_cast<int>(i);
        else if (v.size() > 2 && v.substr(v.size() - 2) == " W" && text::to_number(v.substr(0, v.size() - 2))) watts.push_back(static_cast<int>(i));
        else if (text::to_number(v)) numbers.push_back(static_cast<int>(i));
    }
    if (ts < 0) text::fail(name, line, "no header and no YYYY/MM/DD HH:MM:SS time stamp in the first row; pass columns=timestamp,power.draw,...");
    const bool index_first = ts == 1 && !numbers.empty() && numbers.front() == 0;
    if (index_first) numbers.erase(numbers.begin());
    int power = -1;
    if (watts.size() == 1) power = watts.front();
    else if (watts.empty() && numbers.size() == 1) power = numbers.front();
    if (power < 0)
        text::fail(name, line, "no header, and the power field cannot be told from the others (" + std::to_string(watts.size() + numbers.size()) +
                                   " candidates); pass columns=NAME,... as given to --query-gpu");
    cols.assign(f.size(), "");
    for (std::size_t i = 0; i < f.size(); ++i) cols[i] = "field" + std::to_string(i + 1);
    cols[ts] = "timestamp";
    cols[power] = "power.draw";
    if (index_first) cols[0] = "index";
    return cols;
}

}  // namespace

namespace {

// A data field of an nvidia-smi row: a time stamp, a number, or a number with its unit.
bool data_field(std::string_view v) {
    v = text::trim(v);
    if (text::parse_datetime(v) || text::to_number(v)) return true;
    const auto sp = v.rfind(' ');
    return sp != std::string_view::npos && text::to_number(v.substr(0, sp)).has_value();
}

}  // namespace

PowerTrace parse_nvidia_smi(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (nvidia-smi)";
    OptionReader o(options, parser, {"column", "gpu", "series", "columns", "interval_ms", "max_power_w"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    std::vector<std::string> cols;
    const auto first_fields = text::split(lines[hi].text, ',');
    for (auto f : first_fields) cols.push_back(bare_name(f));
    // --format=csv,noheader: the first line is already a row (a field holds a value).
    const bool headerless = o.text("columns") || std::any_of(first_fields.begin(), first_fields.end(), data_field);
    std::size_t first_row = hi + 1;
    if (headerless) {
        cols = headerless_columns(lines[hi].text, name, lines[hi].number, o);
        first_row = hi;
    }
    auto col = [&](const std::string& n) {
        const auto it = std::find(cols.begin(), cols.end(), n);
        return it == cols.end() ? -1 : static_cast<int>(it - cols.begin());
    };
    const int ct = col("timestamp");
    const auto interval_ms = o.number("interval_ms");
    if (interval_ms && !(*interval_ms > 0)) throw Error(parser + ": option interval_ms must be > 0");
    if (ct < 0 && !interval_ms)
        text::fail(name, lines[hi].number,
                   "the header names no 'timestamp' column: add timestamp to --query-gpu, or pass interval_ms= (the -lms / -l period) to place rows evenly");
    std::string power_name = o.text("column", col("power.draw.instant") >= 0 ? "power.draw.instant" : "power.draw");
    const int cp = col(power_name);
    if (cp < 0) text::fail(name, lines[hi].number, "header has no '" + power_name + "' column");
    // series= (the option every long-form log takes) says the same as gpu=: series=all, or
    // series=KEY=VALUE with KEY the column the GPUs are told apart by (checked below).
    auto gpu = o.text("gpu");
    std::string series_key;
    if (const auto sr = o.text("series")) {
        if (gpu) throw Error(parser + ": give gpu= or series=, not both");
        const auto eq = sr->find('=');
        if (*sr != "all" && (eq == std::string::npos || eq == 0 || eq + 1 == sr->size()))
            throw Error(parser + ": series='" + *sr + "': expected series=all or series=KEY=VALUE (KEY: index, uuid, pci.bus_id or gpu)");
        gpu = *sr == "all" ? *sr : sr->substr(eq + 1);
        if (*sr != "all") series_key = text::lower(sr->substr(0, eq));
    }

    struct Row { std::size_t line; double t; double w; std::vector<std::string> ids; };
    std::vector<Row> rows;
    TraceBuilder b(name, "nvidia-smi");
    // Stamps with a UTC offset ("2025-09-08T17:26:50+08:00") are absolute; zone-less ones are local
    // time. One kind per log: a mix is refused at the first stamp that differs.
    std::optional<bool> zoned;
    // Columns that can tell GPUs apart, in order of preference.
    std::vector<std::pair<std::string, int>> id_cols;
    for (const char* n : {"index", "uuid", "pci.bus_id", "gpu", "gpu_index", "gpu_id", "name"})
        if (col(n) >= 0) id_cols.push_back({n, col(n)});
    for (std::size_t li = first_row; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != cols.size()) {
            if (!headerless && text::trim(l.text) == text::trim(lines[hi].text)) { b.drop(l.number, "repeated header"); continue; }
            text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields as in the header, found " + std::to_string(f.size()));
        }
        double t = 0;
        if (ct >= 0) {
            bool known = false;
            const auto ts = text::parse_datetime(f[ct], &known);
            if (!ts) text::fail(name, l.number, "timestamp '" + std::string(text::trim(f[ct])) + "' is not YYYY/MM/DD HH:MM:SS.mmm");
            if (zoned && *zoned != known)
                text::fail(name, l.number, "timestamp '" + std::string(text::trim(f[ct])) + "' " + (known ? "carries a UTC offset" : "has no time zone") +
                                               " while the rows before it " + (known ? "have none" : "carry one") + ": one kind of stamp per log");
            zoned = known;
            t = *ts;
        }
        std::string_view pv = text::trim(f[cp]);
        if (pv.size() > 2 && pv.substr(pv.size() - 2) == " W") pv.remove_suffix(2);
        const auto w = text::to_number(pv);
        if (!w) {
            b.drop(l.number, "power not available ('" + std::string(text::trim(f[cp])).substr(0, 20) + "')");
            continue;
        }
        std::vector<std::string> ids;
        for (const auto& [n, c] : id_cols) ids.emplace_back(text::trim(f[c]));
        rows.push_back({l.number, t, *w, std::move(ids)});
    }
    if (rows.empty()) throw Error(parser + ": no rows with a power reading");

    // Which GPU each row is: the first id column whose values differ, else the row's position in
    // a burst of rows logged together (a tick), when every burst has the same size.
    std::vector<std::string> device(rows.size());
    std::string told_by;
    std::vector<std::string> devices;  // in order of first appearance
    for (std::size_t k = 0; k < id_cols.size() && told_by.empty(); ++k) {
        std::set<std::string> v;
        for (const auto& r : rows) v.insert(r.ids[k]);
        if (v.size() > 1 && id_cols[k].first != "name") {
            told_by = id_cols[k].first;
            for (std::size_t i = 0; i < rows.size(); ++i) device[i] = rows[i].ids[k];
        }
    }
    // ticks: [begin, end) of rows logged together
    std::vector<std::pair<std::size_t, std::size_t>> ticks;
    if (!told_by.empty()) {
        std::set<std::string> in_tick;
        std::size_t begin = 0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            if (in_tick.count(device[i])) ticks.push_back({begin, i}), in_tick.clear(), begin = i;
            in_tick.insert(device[i]);
        }
        ticks.push_back({begin, rows.size()});
    } else if (rows.size() >= 8 && ct >= 0) {
        // Several GPUs without an id column come as bursts of rows per tick: many intervals far
        // shorter than the typical one.
        std::vector<double> dt;
        for (std::size_t i = 1; i < rows.size(); ++i) dt.push_back(rows[i].t - rows[i - 1].t);
        std::vector<double> sorted = dt;
        std::sort(sorted.begin(), sorted.end());
        const double q75 = sorted[sorted.size() * 3 / 4];
        std::size_t short_count = 0, first_short = 0;
        for (std::size_t i = 0; i < dt.size(); ++i)
            if (dt[i] < q75 / 4 && short_count++ == 0) first_short = rows[i + 1].line;
        if (short_count * 10 >= dt.size() * 3) {
            std::size_t begin = 0;
            for (std::size_t i = 1; i <= rows.size(); ++i)
                if (i == rows.size() || !(dt[i - 1] < q75 / 4)) ticks.push_back({begin, i}), begin = i;
            std::map<std::size_t, std::size_t> sizes;
            for (const auto& [a, e] : ticks) ++sizes[e - a];
            const auto usual = std::max_element(sizes.begin(), sizes.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
            // every tick but a cut-off first or last one holds the usual number of rows
            std::size_t odd = 0, first_odd = 0;
            for (std::size_t k = 0; k < ticks.size(); ++k)
                if (ticks[k].second - ticks[k].first != usual->first && (k > 0 && k + 1 < ticks.size()) && odd++ == 0) first_odd = rows[ticks[k].first].line;
            if (usual->first < 2 || odd)
                text::fail(name, odd ? first_odd : first_short,
                           "rows come in bursts (" + std::to_string(short_count) + " of " + std::to_string(dt.size()) +
                               " intervals < 1/4 of the usual) of unequal sizes: several GPUs logged without an index/uuid column cannot be told apart; add index to --query-gpu");
            told_by = "their order within each burst of rows (no id column)";
            for (const auto& [a, e] : ticks)
                for (std::size_t i = a; i < e; ++i) device[i] = std::to_string(i - a);
        } else {
            ticks.clear();
        }
    }
    for (const auto& d : device)
        if (std::find(devices.begin(), devices.end(), d) == devices.end()) devices.push_back(d);
    const std::size_t n_gpus = told_by.empty() ? 1 : devices.size();
    std::string list;
    for (const auto& d : devices) list += (list.empty() ? "" : ", ") + d;
    if (n_gpus > 1 && !gpu)
        text::fail(name, rows.front().line,
                   "several GPUs in one log: " + std::to_string(n_gpus) + " GPUs in the log (" + list + "); pass gpu=ID for one (told apart by " + told_by +
                       ") or gpu=all for their sum; none is picked silently");
    const bool all = gpu && *gpu == "all";
    if (!series_key.empty()) {
        const std::string by = told_by.empty() ? (id_cols.empty() ? "" : id_cols.front().first) : told_by.rfind("their order", 0) == 0 ? "gpu" : told_by;
        if (series_key != by)
            throw Error(parser + ": series key '" + series_key + "': the GPUs of this log are told apart by " + (by.empty() ? "nothing (one GPU)" : by) +
                        (by.empty() ? "" : "; pass series=" + by + "=VALUE"));
    }
    if (gpu && !all) {
        if (told_by.empty() && id_cols.empty()) throw Error(parser + ": gpu=" + *gpu + " given but the log has no index, uuid or pci.bus_id column");
        if (told_by.empty()) {
            // one GPU: its id must match
            if (rows.front().ids.front() != *gpu)
                throw Error(parser + ": gpu=" + *gpu + " is not in the log (it holds one GPU, " + id_cols.front().first + " " + rows.front().ids.front() + ")");
        } else if (std::find(devices.begin(), devices.end(), *gpu) == devices.end()) {
            throw Error(parser + ": gpu=" + *gpu + " is not in the log (" + std::to_string(n_gpus) + " GPUs: " + list + ")");
        }
    }
    b.power_source("gpu", o, all ? static_cast<double>(n_gpus) : 1.0);
    b.trace().quantity = power_name + (power_name == "power.draw" ? " (the driver's power reading; on recent drivers a 1 s average)" : "");
    b.trace().wall_clock = ct >= 0;
    b.trace().resolution_w = 0.01;
    const double step = interval_ms.value_or(0) * 1e-3;
    if (all && n_gpus > 1) {
        // The sum over each tick holding every GPU once; an incomplete tick at an end is dropped.
        for (std::size_t k = 0; k < ticks.size(); ++k) {
            const auto [a, e] = ticks[k];
            std::set<std::string> seen;
            double sum = 0;
            for (std::size_t i = a; i < e; ++i) seen.insert(device[i]), sum += rows[i].w;
            if (seen.size() != n_gpus || e - a != n_gpus) {
                if (k == 0 || k + 1 == ticks.size()) { b.drop(rows[a].line, "tick at an end of the log without every GPU"); continue; }
                text::fail(name, rows[a].line, "this tick holds " + std::to_string(seen.size()) + " of the " + std::to_string(n_gpus) + " GPUs: their sum is undefined here");
            }
            b.add(rows[a].line, ct >= 0 ? rows[a].t : static_cast<double>(k) * step, sum);
        }
        b.note("power is the sum of " + std::to_string(n_gpus) + " GPUs (gpu=all; told apart by " + told_by + "), each tick at its first row's time stamp");
    } else {
        std::size_t index = 0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            if (gpu && !all && !told_by.empty() && device[i] != *gpu) continue;
            b.add(rows[i].line, ct >= 0 ? rows[i].t : static_cast<double>(index) * step, rows[i].w);
            ++index;
        }
        if (n_gpus > 1) b.note("GPU " + *gpu + " of " + std::to_string(n_gpus) + " in the log (told apart by " + told_by + ")");
    }
    if (ct >= 0 && zoned.value_or(false)) {
        b.note("time stamps carry their UTC offset: read as absolute time");
    } else if (ct >= 0) {
        b.trace().local_time = true;
        b.note("time stamps have no time zone (the logging machine's local time); taken as UTC (timezone= / utc_offset= to convert)");
    } else {
        b.note("no timestamp column: rows placed every interval_ms (" + std::to_string(*interval_ms) + " ms) from 0; timing is only as good as that period");
    }
    return b.finish();
}

}  // namespace trn::energy
