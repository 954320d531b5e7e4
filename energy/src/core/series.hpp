#pragma once
// Long ("tidy") logs: one row per device x domain x time (a rapl-trace log: socket x domain per
// poll). The key columns split the rows into series; several series are never summed or
// interleaved silently: series=KEY=VALUE[|VALUE][,KEY=VALUE] picks one, series=all (or
// series=sum:KEY=VALUE|VALUE,...) sums them per poll. nvidia-smi's gpu= rule, generalised.
// Also energy counters: cumulative readings of one series turned into interval-mean power.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "text_input.hpp"
#include "trace_builder.hpp"

namespace trn::energy::series {

// A series: its (key, value) pairs, in key-column order.
using Key = std::vector<std::pair<std::string, std::string>>;

inline std::string label(const Key& k) {
    std::string s;
    for (const auto& [n, v] : k) s += (s.empty() ? "" : ",") + n + "=" + v;
    return s.empty() ? "(all rows)" : s;
}

// Is a column (not time, not a value column) a key? Text values (not numbers, not dates) with 2..64
// distinct values each seen at least twice, or whole numbers under a key-like name (socket=0/1);
// either way changing at least every 16 rows on average. interleaved() then asks the rows.
inline bool is_key_column(const std::string& column_name, const std::vector<std::string>& values) {
    static const std::set<std::string> key_names = {"socket", "package", "package_id", "pkg", "domain", "zone", "device", "device_id", "dev",
                                                    "gpu", "gpu_id", "gpu_index", "sensor", "rail", "channel", "node", "host", "hostname",
                                                    "machine", "core", "cpu_id", "id", "name", "series"};
    std::map<std::string, std::size_t> count;
    bool numbers = true, whole = true;
    for (const auto& v : values) {
        ++count[v];
        const auto n = text::to_number(v);
        numbers = numbers && n.has_value();
        whole = whole && n && *n == std::trunc(*n);
        if (!n && text::parse_datetime(v)) return false;
    }
    if (count.size() < 2 || count.size() > 64 || values.size() < 4) return false;
    // A label that changes only in long runs (a phase column: idle x 30, busy x 30, ...) describes
    // one device's rows, not series.
    std::size_t changes = 0;
    for (std::size_t i = 1; i < values.size(); ++i) changes += values[i] != values[i - 1];
    if (changes * 16 < values.size()) return false;
    if (numbers) return whole && key_names.count(text::lower(text::trim(column_name))) > 0;
    return std::all_of(count.begin(), count.end(), [](const auto& c) { return c.second >= 2; });
}

struct Selection {
    std::vector<bool> chosen;  // per series
    bool sum = false;
    std::string described;     // for the trace's quantity/notes
};

// RAPL domains nest: package holds core (pp0) and uncore (pp1); psys holds package and dram.
inline void refuse_nested(const std::vector<Key>& all, const std::vector<bool>& chosen, const std::string& parser) {
    auto kind = [](std::string v) {
        v = text::lower(v);
        if (v.rfind("package", 0) == 0 || v == "pkg") return 1;
        if (v == "core" || v == "cores" || v == "pp0" || v == "uncore" || v == "pp1") return 2;
        if (v == "psys" || v == "platform") return 3;
        return 0;
    };
    std::map<std::string, std::set<int>> kinds;  // per key column
    std::map<std::string, std::vector<std::string>> values;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (chosen[i])
            for (const auto& [n, v] : all[i])
                if (kind(v)) kinds[n].insert(kind(v)), values[n].push_back(v);
    for (const auto& [n, k] : kinds)
        if ((k.count(1) && k.count(2)) || (k.count(3) && k.size() > 1)) {
            std::set<std::string> uniq(values[n].begin(), values[n].end());
            std::string list;
            for (const auto& v : uniq) list += (list.empty() ? "" : ", ") + v;
            throw Error(parser + ": the sum would add RAPL domains that contain one another (" + n + ": " + list +
                        "; package holds core/uncore, psys holds package and dram): their joules would count twice; sum only domains that do not "
                        "nest, e.g. series=sum:" + n + "=package|dram");
        }
}

// Parses series= against the log's series. `option` absent: one series is read, several refused.
inline Selection select(const std::vector<Key>& all, const std::optional<std::string>& option, const std::string& parser, const std::string& rows_word) {
    Selection s;
    s.chosen.assign(all.size(), true);
    std::string list;
    for (const auto& k : all) list += (list.empty() ? "" : "; ") + label(k);
    if (!option) {
        if (all.size() > 1)
            throw Error(parser + ": " + std::to_string(all.size()) + " series in one long-form log (" + rows_word + " per " +
                        [&] {
                            std::string keys;
                            for (const auto& [n, v] : all.front()) keys += (keys.empty() ? "" : " x ") + n;
                            return keys;
                        }() +
                        " and time: " + list + "): pass series=KEY=VALUE[,KEY=VALUE] for one, or series=all for their sum per poll; "
                        "none is summed or interleaved silently");
        s.described = all.empty() ? "" : label(all.front());
        return s;
    }
    std::string spec = *option;
    if (spec == "all") {
        s.sum = true;
    } else {
        if (spec.rfind("sum:", 0) == 0) s.sum = true, spec = spec.substr(4);
        for (auto clause : text::split(spec, ',')) {
            const auto eq = clause.find('=');
            if (eq == std::string_view::npos || eq == 0)
                throw Error(parser + ": series='" + *option + "': expected KEY=VALUE[|VALUE][,KEY=VALUE], sum:KEY=VALUE|VALUE or all");
            const std::string key = text::lower(text::trim(clause.substr(0, eq)));
            std::set<std::string> wanted;
            for (auto v : text::split(clause.substr(eq + 1), '|')) wanted.insert(std::string(text::trim(v)));
            bool known = false;
            for (std::size_t i = 0; i < all.size(); ++i) {
                bool match = false;
                for (const auto& [n, v] : all[i])
                    if (text::lower(n) == key) known = true, match = wanted.count(v) > 0;
                s.chosen[i] = s.chosen[i] && match;
            }
            if (!known && !all.empty()) throw Error(parser + ": series='" + *option + "': '" + key + "' is not a key column of this log (series: " + list + ")");
        }
    }
    const auto n = static_cast<std::size_t>(std::count(s.chosen.begin(), s.chosen.end(), true));
    if (n == 0) throw Error(parser + ": series='" + *option + "' matches none of the log's series (" + list + ")");
    std::string picked;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (s.chosen[i]) picked += (picked.empty() ? "" : " + ") + label(all[i]);
    if (n > 1 && !s.sum)
        throw Error(parser + ": series='" + *option + "' leaves " + std::to_string(n) + " series (" + picked +
                    "): name one (add KEY=VALUE), or sum them with series=sum:" + *option);
    if (s.sum) refuse_nested(all, s.chosen, parser);
    s.described = picked;
    return s;
}

// One row's reading: power in W, or a counter in J.
struct Sample {
    std::size_t line = 0;
    double t = 0;
    double v = 0;
    std::size_t series = 0;
};

// Do the series share the log's time? Rows of different series at one time stamp, or a series
// change on at least half of the consecutive rows (each poll's rows in turn). Labels whose rows
// come in blocks (phases of one device) are not series, and the log is one trace.
inline bool interleaved(const std::vector<Sample>& rows) {
    std::size_t changes = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        if (rows[i].series == rows[i - 1].series) continue;
        if (rows[i].t == rows[i - 1].t) return true;
        ++changes;
    }
    return changes * 2 >= rows.size();
}

// A cumulative energy counter per series to interval-mean power: each reading after a series'
// first becomes (E[k] - E[k-1]) / (t[k] - t[k-1]) at t[k]. A step back is a wrap when the range is
// stated (range_j > 0: powercap's max_energy_range_uj), else refused naming the line: a counter
// running backwards is a reset, a wrap or a unit error, never negative energy. The first reading of
// each series starts its first interval (returned per series in `start`).
inline std::vector<Sample> counter_to_power(const std::vector<Sample>& in, std::size_t n_series, double range_j, const std::string& file,
                                            const std::string& column, std::vector<std::optional<double>>& start, std::size_t& wraps,
                                            TraceBuilder& b) {
    std::vector<std::optional<Sample>> prev(n_series);
    start.assign(n_series, std::nullopt);
    std::vector<Sample> out;
    for (const auto& s : in) {
        auto& p = prev[s.series];
        if (!p) {
            p = s;
            start[s.series] = s.t;
            continue;
        }
        if (s.t == p->t) {
            b.drop(s.line, "same time stamp as the series' reading before (counter)");
            continue;
        }
        if (s.t < p->t) text::fail(file, s.line, "time goes backwards within a series (" + std::to_string(s.t) + " s after " + std::to_string(p->t) + " s)");
        double d = s.v - p->v;
        if (d < 0) {
            char buf[400];
            if (!(range_j > 0)) {
                std::snprintf(buf, sizeof buf, "energy counter '%s' runs backwards (from %.10g J at line %zu to %.10g J): a reset, a wrap, or not a "
                              "running total (energy per interval is not read as a counter); pass max_energy_range_uj= (powercap's "
                              "max_energy_range_uj) if the counter wraps", column.c_str(), p->v, p->line, s.v);
                text::fail(file, s.line, buf);
            }
            d += range_j;
            if (d < 0) {
                std::snprintf(buf, sizeof buf, "energy counter '%s' steps back by more than its range (max_energy_range_uj) from line %zu", column.c_str(), p->line);
                text::fail(file, s.line, buf);
            }
            ++wraps;
        }
        out.push_back({s.line, s.t, d / (s.t - p->t), s.series});
        p = s;
    }
    return out;
}

// The chosen series' samples, in file order, summed per poll: a poll is a run of rows with
// distinct series (a series seen again starts the next). A poll without every chosen series is
// dropped at either end of the log and refused elsewhere. Returns (line, t of its first row, sum).
inline std::vector<Sample> sum_per_poll(const std::vector<Sample>& in, const std::vector<bool>& chosen, const std::string& file, TraceBuilder& b) {
    const auto n = static_cast<std::size_t>(std::count(chosen.begin(), chosen.end(), true));
    std::vector<std::vector<Sample>> polls;
    std::set<std::size_t> seen;
    for (const auto& s : in) {
        if (!chosen[s.series]) continue;
        if (polls.empty() || seen.count(s.series)) polls.emplace_back(), seen.clear();
        polls.back().push_back(s);
        seen.insert(s.series);
    }
    std::vector<Sample> out;
    for (std::size_t k = 0; k < polls.size(); ++k) {
        const auto& p = polls[k];
        if (p.size() != n) {
            if (k == 0 || k + 1 == polls.size()) {
                b.drop(p.front().line, "poll at an end of the log without every series");
                continue;
            }
            text::fail(file, p.front().line, "this poll holds " + std::to_string(p.size()) + " of the " + std::to_string(n) + " series: their sum is undefined here");
        }
        double sum = 0;
        for (const auto& s : p) sum += s.v;
        out.push_back({p.front().line, p.front().t, sum, 0});
    }
    return out;
}

}  // namespace trn::energy::series
