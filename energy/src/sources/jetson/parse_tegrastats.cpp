// tegrastats logs of the TX1/TX2, Nano, Xavier and Orin generations.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

// A Jetson module's input rail holds every other rail of the module: a sum of rails must leave
// it out (or be it alone), else the joules inside it count twice.
bool input_rail(std::string_view n) { return n == "VDD_IN" || n == "POM_5V_IN"; }

bool rail_name(std::string_view s) {
    if (s.size() < 4) return false;
    for (char c : s)
        if (!(std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_')) return false;
    return s.find('_') != std::string_view::npos;
}

// "3566/3566" or "5542mW/5542mW" -> current mW
std::optional<double> rail_value(std::string_view s) {
    const auto slash = s.find('/');
    if (slash == std::string_view::npos) return std::nullopt;
    std::string_view cur = s.substr(0, slash), avg = s.substr(slash + 1);
    for (std::string_view* p : {&cur, &avg})
        if (p->size() > 2 && p->substr(p->size() - 2) == "mW") p->remove_suffix(2);
    const auto c = text::to_number(cur);
    if (!c || !text::to_number(avg)) return std::nullopt;
    return c;
}

}  // namespace

PowerTrace parse_tegrastats(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (tegrastats)";
    OptionReader o(options, parser, {"rail", "interval_ms", "max_power_w"});
    const std::string rail = o.text("rail", "");
    const auto interval_given = o.number("interval_ms");
    const double interval = interval_given.value_or(1000) * 1e-3;
    if (!(interval > 0)) throw Error(parser + ": interval_ms must be > 0");
    struct Entry { std::size_t line; std::optional<double> stamp; double w; };
    std::vector<Entry> entries;
    TraceBuilder b(name, "tegrastats");
    b.power_source("soc", o);
    b.trace().resolution_w = 1e-3;
    std::size_t stamped = 0, unstamped = 0, index = 0;
    std::string rule, sum_rails;
    std::size_t sum_line = 0;
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (s.empty()) continue;
        const auto ram = s.find("RAM ");
        if (ram == std::string_view::npos) {
            b.drop(l.number, "not a tegrastats line (prompt, date or other text)");
            continue;
        }
        std::optional<double> t;
        if (ram > 0) {
            t = text::parse_datetime(s.substr(0, ram));
            if (!t) text::fail(name, l.number, "text before 'RAM' is not an MM-DD-YYYY HH:MM:SS time stamp");
        }
        std::map<std::string, double> rails;
        const auto tok = text::split_ws(s.substr(ram));
        for (std::size_t i = 0; i + 1 < tok.size(); ++i)
            if (rail_name(tok[i]))
                if (const auto v = rail_value(tok[i + 1])) rails[std::string(tok[i])] = *v;
        if (rails.empty()) text::fail(name, l.number, "no power rails (NAME cur/avg) on this line");
        double mw = 0;
        std::string used;
        if (rail == "sum") {
            std::string names, left_out;
            for (const auto& [n, v] : rails) {
                if (input_rail(n)) { left_out += (left_out.empty() ? "" : ", ") + n; continue; }
                mw += v, names += (names.empty() ? "" : "+") + n;
            }
            used = left_out.empty() ? "sum of all rails" : "sum of rails " + names + " (input rail " + left_out + " left out: it holds them)";
        } else if (!rail.empty()) {
            const auto it = rails.find(rail);
            if (it == rails.end()) text::fail(name, l.number, "rail '" + rail + "' is not on this line");
            mw = it->second;
            used = rail;
        } else if (rails.count("VDD_IN")) {
            mw = rails["VDD_IN"], used = "VDD_IN (input rail)";
        } else if (rails.count("POM_5V_IN")) {
            mw = rails["POM_5V_IN"], used = "POM_5V_IN (input rail)";
        } else {
            for (const auto& [n, v] : rails) mw += v;
            used = "sum of all rails (no input rail in this log, as on AGX Orin)";
        }
        if (rule.empty()) rule = used;
        else if (rule != used) text::fail(name, l.number, "total rule changed from '" + rule + "' to '" + used + "' (rails differ between lines)");
        // A sum is only comparable between lines that add the same rails: a line missing one
        // would read as a power drop, so it is refused.
        if (used.starts_with("sum")) {
            std::string names;
            for (const auto& [n, v] : rails) names += (names.empty() ? "" : " ") + n;
            if (sum_rails.empty()) sum_rails = names, sum_line = l.number;
            else if (names != sum_rails)
                text::fail(name, l.number, "summed rails '" + names + "' differ from '" + sum_rails + "' at line " + std::to_string(sum_line) +
                                               " (a rail missing or added): the sum would not be the same quantity");
        }
        if (t) ++stamped; else ++unstamped;
        if (stamped && unstamped) text::fail(name, l.number, "some lines have time stamps and some do not");
        entries.push_back({l.number, t, mw * 1e-3});
    }
    // JetPack 6 stamps have 1 s resolution: at --interval 100 or 500 several lines share one. The
    // lines of a stamp are placed interval_ms apart (else 1 s / the usual count per stamp) from
    // the start of their second; the first stamp's lines are the last of their second.
    std::size_t shared = 0, crowded = 0, largest = 1;
    double spacing = interval;
    if (stamped) {
        std::vector<std::pair<std::size_t, std::size_t>> groups;  // [begin, end) of equal stamps
        for (std::size_t i = 0; i < entries.size();) {
            std::size_t k = i + 1;
            while (k < entries.size() && *entries[k].stamp == *entries[i].stamp) ++k;
            groups.push_back({i, k});
            largest = std::max(largest, k - i);
            if (k - i > 1) shared += k - i;
            i = k;
        }
        if (shared && !interval_given) {
            std::vector<std::size_t> sizes;
            for (std::size_t g = groups.size() > 2 ? 1 : 0; g < (groups.size() > 2 ? groups.size() - 1 : groups.size()); ++g)
                sizes.push_back(groups[g].second - groups[g].first);
            std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
            spacing = 1.0 / static_cast<double>(sizes[sizes.size() / 2]);
        }
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const auto [begin, end] = groups[g];
            const std::size_t n = end - begin;
            const bool fits = static_cast<double>(n) * spacing <= 1 + 1e-9;
            if (!fits) ++crowded;
            for (std::size_t j = 0; j < n; ++j) {
                const Entry& e = entries[begin + j];
                double t = *e.stamp;
                if (n > 1 || shared) {
                    if (!fits) t += static_cast<double>(j) / static_cast<double>(n);
                    else if (g == 0 && groups.size() > 1) t += 1 - static_cast<double>(n - j) * spacing;
                    else t += static_cast<double>(j) * spacing;
                }
                b.add(e.line, t, e.w);
            }
        }
    } else {
        for (const Entry& e : entries) b.add(e.line, static_cast<double>(index++) * interval, e.w);
    }
    b.trace().quantity = rule;
    b.trace().wall_clock = stamped > 0;
    if (unstamped)
        b.note("lines carry no time stamps: sample i is placed at i x " + std::to_string(interval * 1e3) +
               " ms (assumed tegrastats --interval); timing is only as good as that assumption");
    b.trace().local_time = stamped > 0;
    if (stamped) b.note("time stamps have 1 s resolution and no time zone; taken as UTC (timezone= / utc_offset= to convert)");
    if (shared) {
        char buf[400];
        std::snprintf(buf, sizeof buf, "%zu lines share their 1 s time stamp with others (up to %zu per stamp): placed %.4g ms apart within their second (%s)%s",
                      shared, largest, spacing * 1e3, interval_given ? "interval_ms" : "1 s / the usual count per stamp; interval_ms= to state the --interval",
                      crowded ? "; stamps with more lines than fit are spread evenly over their second" : "");
        b.note(buf);
    }
    return b.finish();
}

// jetson-stats (jtop) CSV: csv.DictWriter over jtop's `stats`, a header "time,uptime,CPU1,...,
// Power <RAIL>,...,Power TOT,jetson_clocks,nvp model", power in mW, time a zone-less local
// datetime. rail=NAME picks a rail, rail=sum the rails outside the input rail; default Power TOT.
bool looks_like_jtop(std::string_view input) {
    const auto nl = input.find('\n');
    const std::string head = text::lower(input.substr(0, nl == std::string_view::npos ? std::min<std::size_t>(input.size(), 4096) : nl));
    return text::starts_with(head, "time,") && head.find(",uptime,") != std::string::npos && head.find(",power ") != std::string::npos;
}

PowerTrace parse_jtop(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (jtop)";
    OptionReader o(options, parser, {"rail", "max_power_w"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    const auto cols = text::split_fields(lines[hi].text, ',');
    int ct = -1;
    std::vector<std::pair<std::string, int>> rails;  // "Power X" columns but TOT
    int c_tot = -1;
    for (std::size_t i = 0; i < cols.size(); ++i) {
        if (text::lower(cols[i]) == "time") ct = static_cast<int>(i);
        if (cols[i].rfind("Power ", 0) == 0) {
            const std::string r = cols[i].substr(6);
            if (r == "TOT") c_tot = static_cast<int>(i);
            else rails.push_back({r, static_cast<int>(i)});
        }
    }
    if (ct < 0) text::fail(name, lines[hi].number, "no 'time' column (a jtop CSV starts time,uptime,...)");
    std::string list;
    for (const auto& [r, c] : rails) list += (list.empty() ? "" : ", ") + r;
    const std::string rail = o.text("rail", c_tot >= 0 ? "TOT" : "");
    std::vector<int> use;
    std::string quantity;
    if (rail.empty()) {
        text::fail(name, lines[hi].number, "no 'Power TOT' column: pass rail=NAME (one of " + list + ") or rail=sum (the rails outside the input rail)");
    } else if (rail == "TOT") {
        if (c_tot < 0) text::fail(name, lines[hi].number, "rail=TOT but the log has no 'Power TOT' column (rails: " + list + ")");
        use.push_back(c_tot);
        quantity = "Power TOT (jtop's total)";
    } else if (rail == "sum") {
        std::string names, left_out;
        for (const auto& [r, c] : rails) {
            if (input_rail(r)) { left_out += (left_out.empty() ? "" : ", ") + r; continue; }
            use.push_back(c), names += (names.empty() ? "" : "+") + r;
        }
        if (use.empty()) text::fail(name, lines[hi].number, "rail=sum: no rails besides the input rail (" + left_out + ")");
        quantity = "sum of rails " + names + (left_out.empty() ? "" : " (input rail " + left_out + " left out: it holds them)");
    } else {
        for (const auto& [r, c] : rails)
            if (r == rail) use.push_back(c);
        if (use.empty()) text::fail(name, lines[hi].number, "rail '" + rail + "' is not in the log (rails: " + list + (c_tot >= 0 ? ", TOT" : "") + ")");
        quantity = "Power " + rail;
    }
    TraceBuilder b(name, "jtop");
    b.power_source("soc", o);
    b.trace().quantity = quantity + " (mW)";
    b.trace().wall_clock = b.trace().local_time = true;
    b.trace().resolution_w = 1e-3;
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split_fields(l.text, ',');
        if (f.size() != cols.size())
            text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields as in the header, found " + std::to_string(f.size()));
        bool zoned = false;
        const auto t = text::parse_datetime(f[static_cast<std::size_t>(ct)], &zoned);
        if (!t) text::fail(name, l.number, "time '" + f[static_cast<std::size_t>(ct)].substr(0, 40) + "' is not YYYY-MM-DD HH:MM:SS[.ffffff]");
        if (zoned) b.trace().local_time = false;
        double mw = 0;
        bool ok = true;
        for (int c : use) {
            const auto v = text::to_number(f[static_cast<std::size_t>(c)]);
            ok = ok && v.has_value();
            if (v) mw += *v;
        }
        if (!ok) {
            b.drop(l.number, "power field empty or not a number");
            continue;
        }
        b.add(l.number, *t, mw * 1e-3);
    }
    b.note("jtop power in mW; rail=" + rail + (rail == "TOT" ? " (default; rail=NAME or rail=sum for others: " + list + ")" : ""));
    if (b.trace().local_time) b.note("time stamps have no time zone (jtop writes the board's local time); taken as UTC (timezone= / utc_offset= to convert)");
    return b.finish();
}

}  // namespace trn::energy
