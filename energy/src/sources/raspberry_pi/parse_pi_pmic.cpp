// Raspberry Pi 5 PMIC readings: `vcgencmd pmic_read_adc` dumps ("VDD_CORE_A current(7)=0.72300000A",
// "VDD_CORE_V volt(15)=0.87900000V"), each after a time stamp line a logging loop wrote
// (`date +%s.%N`, `date --iso-8601=ns`, or any ISO stamp). Power = the sum over the rails that have
// both a current and a voltage of I x V.
#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "option_reader.hpp"
#include "pi_pmic.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace pmic {

std::optional<Reading> parse_line(std::string_view s) {
    s = text::trim(s);
    const auto sp = s.find(' ');
    const auto eq = s.find(")=");
    if (sp == std::string_view::npos || eq == std::string_view::npos || eq < sp) return std::nullopt;
    const std::string_view name = s.substr(0, sp), kind = text::trim(s.substr(sp + 1, eq - sp));
    std::string_view value = s.substr(eq + 2);
    Reading r;
    if (kind.rfind("current(", 0) == 0 && name.size() > 2 && name.substr(name.size() - 2) == "_A" && !value.empty() && value.back() == 'A') {
        r.current = true;
    } else if (kind.rfind("volt(", 0) == 0 && name.size() > 2 && name.substr(name.size() - 2) == "_V" && !value.empty() && value.back() == 'V') {
        r.current = false;
    } else {
        return std::nullopt;
    }
    value.remove_suffix(1);
    const auto v = text::to_number(value);
    if (!v) return std::nullopt;
    r.rail = std::string(name.substr(0, name.size() - 2));
    r.value = *v;
    return r;
}

Sum sum(const Dump& d) {
    Sum s;
    for (const auto& [rail, a] : d.amps) {
        const auto v = d.volts.find(rail);
        if (v == d.volts.end()) {
            s.unpaired.insert(rail + "_A");
            continue;
        }
        s.w += a * v->second, s.rails += (s.rails.empty() ? "" : "+") + rail;
    }
    for (const auto& [rail, v] : d.volts)
        if (!d.amps.count(rail)) s.unpaired.insert(rail + "_V");
    return s;
}

}  // namespace pmic

bool looks_like_pi_pmic(std::string_view input) {
    std::size_t seen = 0;
    for (const auto& l : text::split_lines(input.substr(0, std::min<std::size_t>(input.size(), 8192))))
        if (pmic::parse_line(l.text) && ++seen >= 2) return true;
    return false;
}

PowerTrace parse_pi_pmic(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (pi5-pmic)";
    OptionReader o(options, parser, {"interval_s", "max_power_w"});
    const auto interval = o.number("interval_s");
    if (interval && !(*interval > 0)) throw Error(parser + ": option interval_s must be > 0");
    TraceBuilder b(name, "pi5-pmic");
    b.power_source("node", o);
    b.trace().quantity = "sum of PMIC rails I x V (vcgencmd pmic_read_adc)";
    struct Dump : pmic::Dump { std::size_t line = 0; std::optional<double> t; };
    std::vector<Dump> dumps;
    bool stamped = false, any_zone_less = false;
    auto start = [&](std::size_t line, std::optional<double> t) {
        dumps.push_back({});
        dumps.back().line = line;
        dumps.back().t = t;
    };
    for (const auto& l : text::split_lines(input)) {
        const auto s = text::trim(l.text);
        if (s.empty() || s.front() == '#') continue;
        if (const auto r = pmic::parse_line(s)) {
            if (dumps.empty() || (!stamped && (r->current ? dumps.back().amps : dumps.back().volts).count(r->rail))) start(l.number, std::nullopt);
            auto& d = dumps.back();
            auto& m = r->current ? d.amps : d.volts;
            if (m.count(r->rail)) text::fail(name, l.number, "rail " + r->rail + (r->current ? "_A" : "_V") + " twice in one dump without a time stamp between");
            m[r->rail] = r->value;
            continue;
        }
        // a time stamp line: UNIX seconds (date +%s.%N) or an ISO date-time
        bool zoned = false;
        std::optional<double> t = text::to_number(s);
        if (!t) t = text::parse_datetime(s, &zoned);
        else zoned = true;
        if (!t) text::fail(name, l.number, "expected a PMIC reading ('NAME_A current(N)=xA' / 'NAME_V volt(N)=xV') or a time stamp line (date +%s.%N)");
        if (!zoned) any_zone_less = true;
        stamped = true;
        start(l.number, t);
    }
    std::set<std::string> unpaired;
    std::string summed;
    std::size_t index = 0;
    for (const auto& d : dumps) {
        if (d.empty()) continue;
        const pmic::Sum sm = pmic::sum(d);
        const double w = sm.w;
        const std::string& rails = sm.rails;
        unpaired.insert(sm.unpaired.begin(), sm.unpaired.end());
        if (summed.empty()) summed = rails;
        else if (rails != summed)
            text::fail(name, d.line, "this dump's rails (" + rails + ") differ from the first dump's (" + summed + "): the sum would not be the same quantity");
        double t = 0;
        if (stamped) {
            if (!d.t) text::fail(name, d.line, "PMIC readings before the first time stamp line");
            t = *d.t;
        } else if (interval) {
            t = static_cast<double>(index) * *interval;
        } else {
            text::fail(name, d.line, "PMIC dumps without time stamps: log `date +%s.%N` before each `vcgencmd pmic_read_adc`, or pass interval_s= "
                                     "(the loop's period) to place them evenly");
        }
        ++index;
        b.add(d.line, t, w);
    }
    if (stamped) {
        b.trace().wall_clock = true;
        b.trace().local_time = any_zone_less;
        if (any_zone_less) b.note("time stamps have no time zone; taken as UTC (timezone= / utc_offset= to convert)");
    } else {
        b.note("no time stamps: dumps placed every interval_s from 0");
    }
    std::string left;
    for (const auto& u : unpaired) left += (left.empty() ? "" : ", ") + u;
    b.note("power = sum of I x V over the PMIC rails " + summed + " (each dump read at once, instant)" +
           (left.empty() ? "" : "; left out, without a partner reading: " + left) +
           "; " + pmic::kNotInSum);
    return b.finish();
}

}  // namespace trn::energy
