// tegrastats logs of the TX1/TX2, Nano, Xavier and Orin generations.
#include <cctype>
#include <map>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

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
    OptionReader o(options, parser, {"rail", "interval_ms"});
    const std::string rail = o.text("rail", "");
    const double interval = o.number("interval_ms", 1000) * 1e-3;
    if (!(interval > 0)) throw Error(parser + ": interval_ms must be > 0");
    TraceBuilder b(name, "tegrastats");
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
            for (const auto& [n, v] : rails) mw += v;
            used = "sum of all rails";
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
        b.add(l.number, t ? *t : index * interval, mw * 1e-3);
        ++index;
    }
    b.trace().quantity = rule;
    b.trace().wall_clock = stamped > 0;
    if (unstamped)
        b.note("lines carry no time stamps: sample i is placed at i x " + std::to_string(interval * 1e3) +
               " ms (assumed tegrastats --interval); timing is only as good as that assumption");
    b.trace().local_time = stamped > 0;
    if (stamped) b.note("time stamps have 1 s resolution and no time zone; taken as UTC (--timezone/--utc-offset to convert)");
    return b.finish();
}

}  // namespace trn::energy
