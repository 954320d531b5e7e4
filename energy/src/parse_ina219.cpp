// INA219 logs: engineering-unit CSV, Arduino Python-tuple lines, and raw registers.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/ina219.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

using text::Line;

bool is_comment(std::string_view l) {
    l = text::trim(l);
    return l.empty() || l.front() == '#';
}

char detect_delimiter(std::string_view line) {
    for (char c : {',', ';', '\t'})
        if (line.find(c) != std::string_view::npos) return c;
    return ',';
}

// Unit scale read from a column name's suffix ("current_mA", "power [W]", "bus(V)").
std::optional<double> unit_scale_from_name(const std::string& name) {
    const std::string n = text::lower(name);
    for (const auto& [suffix, scale] : std::vector<std::pair<std::string, double>>{
             {"mv", 1e-3}, {"uv", 1e-6}, {"ma", 1e-3}, {"ua", 1e-6}, {"mw", 1e-3}, {"uw", 1e-6}, {"v", 1}, {"a", 1}, {"w", 1}}) {
        for (const std::string& wrap : {"_" + suffix, "[" + suffix + "]", "(" + suffix + ")", " " + suffix})
            if (n.size() >= wrap.size() && n.compare(n.size() - wrap.size(), wrap.size(), wrap) == 0) return scale;
    }
    return std::nullopt;
}

double unit_scale(const std::string& unit, const std::string& option, const std::string& parser) {
    static const std::map<std::string, double> scales = {{"v", 1}, {"mv", 1e-3}, {"uv", 1e-6}, {"a", 1}, {"ma", 1e-3},
                                                         {"ua", 1e-6}, {"w", 1}, {"mw", 1e-3}, {"uw", 1e-6}};
    const auto it = scales.find(text::lower(unit));
    if (it == scales.end()) throw Error(parser + ": option " + option + "='" + unit + "' is not a unit (V, mV, A, mA, W, mW ...)");
    return it->second;
}

struct Column {
    int index = -1;
    double scale = 1;
    std::string name;
};

// Median of the steps between consecutive increasing times (0 when there are none).
double median_step(const std::vector<double>& t) {
    std::vector<double> d;
    for (std::size_t i = 1; i < t.size(); ++i)
        if (t[i] > t[i - 1]) d.push_back(t[i] - t[i - 1]);
    if (d.empty()) return 0;
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    return d[d.size() / 2];
}

}  // namespace

PowerTrace parse_ina219_csv(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (ina219-csv)";
    OptionReader o(options, parser, {"columns", "time", "bus_v", "shunt_v", "current", "power", "time_unit", "period_s",
                                     "bus_v_unit", "current_unit", "power_unit", "use"});
    const auto lines = text::split_lines(input);
    std::size_t first = 0;
    while (first < lines.size() && is_comment(lines[first].text)) ++first;
    if (first == lines.size()) throw Error(parser + ": no data lines");
    const char delim = detect_delimiter(lines[first].text);

    std::vector<std::string> names;
    std::size_t data_start = first;
    if (const auto cols = o.text("columns")) {
        for (auto c : text::split(*cols, ',')) names.emplace_back(text::trim(c));
    } else {
        const auto fields = text::split(lines[first].text, delim);
        const bool header = std::none_of(fields.begin(), fields.end(), [](std::string_view f) {
            return text::to_number(f) || text::parse_datetime(f);
        });
        if (!header)
            text::fail(name, lines[first].number,
                       "no header row naming the columns; pass columns=... (e.g. columns=index,sensor,bus_V,current_mA,power_W)");
        for (auto f : fields) names.emplace_back(text::trim(f));
        data_start = first + 1;
    }
    auto find = [&](const std::string& option, const std::function<bool(const std::string&)>& match) {
        Column c;
        if (const auto wanted = o.text(option)) {
            for (std::size_t i = 0; i < names.size(); ++i)
                if (text::lower(names[i]) == text::lower(*wanted)) c.index = static_cast<int>(i);
            if (c.index < 0) throw Error(parser + ": option " + option + "='" + *wanted + "' names no column");
        } else {
            for (std::size_t i = 0; i < names.size() && c.index < 0; ++i)
                if (match(text::lower(names[i]))) c.index = static_cast<int>(i);
        }
        if (c.index >= 0) c.name = names[c.index];
        return c;
    };
    auto has = [](const std::string& s, const char* w) { return s.find(w) != std::string::npos; };
    Column time = find("time", [&](const std::string& n) { return has(n, "time") || n == "t" || has(n, "elapsed") || n == "index" || n == "idx"; });
    Column shunt = find("shunt_v", [&](const std::string& n) { return has(n, "shunt"); });
    Column power = find("power", [&](const std::string& n) { return has(n, "power") || n == "p" || n == "w" || n == "mw"; });
    Column current = find("current", [&](const std::string& n) {
        return (has(n, "current") || n == "i" || n == "ma" || n == "a" || n == "i_ma" || n == "current_ma") && !has(n, "shunt");
    });
    Column bus = find("bus_v", [&](const std::string& n) {
        return (has(n, "bus") || has(n, "volt") || n == "v" || n == "v_bus") && !has(n, "shunt");
    });
    if (time.index < 0) throw Error(parser + ": no time column among '" + std::string(lines[first].text.substr(0, 200)) + "'; pass time=NAME");
    auto set_scale = [&](Column& c, const std::string& unit_option, double fallback) {
        if (c.index < 0) return;
        if (const auto u = o.text(unit_option)) c.scale = unit_scale(*u, unit_option, parser);
        else c.scale = unit_scale_from_name(c.name).value_or(fallback);
    };
    set_scale(bus, "bus_v_unit", 1.0);
    set_scale(current, "current_unit", 1e-3);  // INA219 libraries report mA
    set_scale(power, "power_unit", 1e-3);      // ... and mW
    const std::string use = o.text("use", "vi");
    if (use != "vi" && use != "power") throw Error(parser + ": option use must be vi or power");
    const bool vi = bus.index >= 0 && current.index >= 0 && !(use == "power" && power.index >= 0);
    if (!vi && power.index < 0) throw Error(parser + ": needs a power column or bus voltage and current columns");

    std::string time_unit = o.text("time_unit", "");
    const std::string tname = text::lower(time.name);
    if (time_unit.empty()) {
        if (tname == "index" || tname == "idx") time_unit = "index";
        else if (has(tname, "_ms") || has(tname, "[ms]")) time_unit = "ms";
        else if (has(tname, "_us") || has(tname, "[us]")) time_unit = "us";
        else time_unit = "auto";  // seconds or ISO date, decided by the first row
    }
    const double period = o.number("period_s", 0);
    if (time_unit == "index" && !(period > 0)) throw Error(parser + ": time column '" + time.name + "' is a row index; pass period_s=SECONDS");

    TraceBuilder b(name, "ina219-csv");
    b.trace().quantity = vi ? bus.name + "*" + current.name : power.name;
    std::size_t bad = 0, first_bad = 0;
    std::vector<double> vi_ratio;
    bool zone_known = true;
    for (std::size_t li = data_start; li < lines.size(); ++li) {
        const Line& l = lines[li];
        if (is_comment(l.text)) continue;
        const auto f = text::split(l.text, delim);
        auto get = [&](const Column& c) -> std::optional<double> {
            if (c.index < 0 || static_cast<std::size_t>(c.index) >= f.size()) return std::nullopt;
            const auto v = text::to_number(f[c.index]);
            return v ? std::optional<double>(*v * c.scale) : std::nullopt;
        };
        std::optional<double> t;
        if (static_cast<std::size_t>(time.index) < f.size()) {
            const std::string_view tf = f[time.index];
            if (time_unit == "auto") {
                if (auto n = text::to_number(tf)) t = n;
                else if (auto d = text::parse_datetime(tf, &zone_known)) { t = d; b.trace().wall_clock = true; }
            } else if (time_unit == "iso") {
                if (auto d = text::parse_datetime(tf, &zone_known)) { t = d; b.trace().wall_clock = true; }
            } else if (auto n = text::to_number(tf)) {
                t = time_unit == "ms" ? *n * 1e-3 : time_unit == "us" ? *n * 1e-6 : time_unit == "index" ? *n * period : *n;
            }
        }
        std::optional<double> w;
        if (vi) {
            const auto v = get(bus), i = get(current);
            if (v && i) w = *v * *i;
            if (const auto p = get(power); w && p && std::abs(*w) > 1e-3) vi_ratio.push_back(*p / *w);
        } else {
            w = get(power);
        }
        if (!t || !w) {
            if (bad++ == 0) first_bad = l.number;
            b.drop(l.number, "missing or unreadable time/power fields");
            continue;
        }
        b.add(l.number, *t, *w);
    }
    if (bad * 2 > lines.size() - data_start && bad > 0)
        text::fail(name, first_bad, "most rows are unreadable (" + std::to_string(bad) + "); check columns/delimiter");
    if (!vi_ratio.empty()) {
        std::nth_element(vi_ratio.begin(), vi_ratio.begin() + vi_ratio.size() / 2, vi_ratio.end());
        const double r = vi_ratio[vi_ratio.size() / 2];
        if (r < 0.5 || r > 2) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "power column '%s' is %.4g x bus*current (median): a logger unit bug? using V*I", power.name.c_str(), r);
            b.note(buf);
        }
    }
    b.trace().local_time = b.trace().wall_clock && !zone_known;
    if (b.trace().local_time) b.note("time stamps have no time zone; taken as UTC (--timezone/--utc-offset to convert)");
    if (!b.trace().w.empty() && *std::min_element(b.trace().w.begin(), b.trace().w.end()) < 0)
        b.note("negative power readings present (shunt offset or reverse current); kept as read");
    return b.finish();
}

PowerTrace parse_ina219_tuples(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (ina219-tuples)";
    OptionReader o(options, parser, {"tick_period_s", "tick_bits", "max_bus_v"});
    const double tick = o.number("tick_period_s", 0);
    const double bits = o.number("tick_bits", 16);
    if (bits < 8 || bits > 32 || bits != std::trunc(bits)) throw Error(parser + ": tick_bits must be an integer 8..32");
    const double wrap = std::ldexp(1.0, static_cast<int>(bits));
    const double max_bus = o.number("max_bus_v", 16);
    TraceBuilder b(name, "ina219-tuples");
    b.trace().quantity = "bus_V*current_mA";
    b.trace().resolution_w = 0;
    double last_tick = -1, wraps = 0;
    for (const Line& l : text::split_lines(input)) {
        std::string_view s = text::trim(l.text);
        if (s.empty()) continue;
        if (s.front() != '(' || s.back() != ')') text::fail(name, l.number, "expected a tuple '(t, bus_V, current_mA, power_mW)'");
        const auto f = text::split(s.substr(1, s.size() - 2), ',');
        if (f.size() != 4) text::fail(name, l.number, "expected 4 fields in the tuple, found " + std::to_string(f.size()));
        double v[4];
        for (int i = 0; i < 4; ++i) {
            const auto n = text::to_number(f[i]);
            if (!n) text::fail(name, l.number, "field " + std::to_string(i + 1) + " '" + std::string(text::trim(f[i])) + "' is not a number");
            v[i] = *n;
        }
        if (v[0] == 0 && v[1] == 0 && v[2] == 0 && v[3] == 0) {
            b.drop(l.number, "all-zero sentinel row");
            continue;
        }
        double t = v[0];
        if (tick > 0) {
            if (v[0] < 0 || v[0] >= wrap || v[0] != std::trunc(v[0])) text::fail(name, l.number, "tick '" + std::string(text::trim(f[0])) + "' is not a " + std::to_string(static_cast<int>(bits)) + "-bit counter value");
            if (last_tick >= 0 && v[0] < last_tick) wraps += 1;
            last_tick = v[0];
            t = (v[0] + wraps * wrap) * tick;
        } else if (!b.trace().t.empty() && t < b.trace().t.back() && v[0] == std::trunc(v[0]) && v[0] < 4294967296.0) {
            text::fail(name, l.number, "time goes backwards: the first field looks like a wrapping timer tick; pass tick_period_s=SECONDS");
        }
        if (v[1] > max_bus) {
            b.drop(l.number, "bus voltage above max_bus_v (a glitch)");
            continue;
        }
        if (v[1] == 0 && v[2] != 0) {
            b.drop(l.number, "bus voltage reads 0 V while current flows (a misread)");
            continue;
        }
        b.add(l.number, t, v[1] * v[2] * 1e-3);
    }
    if (tick > 0) {
        b.note("time from a " + std::to_string(static_cast<int>(bits)) + "-bit tick unwrapped " + std::to_string(static_cast<int>(wraps)) +
               " time(s); a gap longer than one wrap period (" + std::to_string(wrap * tick) + " s) would be invisible");
    }
    return b.finish();
}

PowerTrace parse_ina219_raw(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (ina219-raw)";
    const auto lines = text::split_lines(input);
    // Settings written in "# key=value" comment lines (as the simulator does); options override.
    ParseOptions merged;
    std::string use = "vi";
    for (const auto& l : lines) {
        const auto s = text::trim(l.text);
        if (s.empty() || s.front() != '#') continue;
        for (auto tok : text::split_ws(s.substr(1))) {
            const auto eq = tok.find('=');
            if (eq == std::string_view::npos) continue;
            const std::string key(tok.substr(0, eq));
            if (key == "shunt_ohm" || key == "current_lsb" || key == "cal" || key == "pga_mv" || key == "adc")
                merged[key] = std::string(tok.substr(eq + 1));
        }
    }
    std::string time_ref = "adc";
    for (const auto& [k, v] : options) {
        if (k == "time_ref") time_ref = v;
        else merged[k] = v;
    }
    if (time_ref != "adc" && time_ref != "read") throw Error(parser + ": option time_ref must be adc or read");
    if (auto it = merged.find("use"); it != merged.end()) use = it->second;
    if (use != "vi" && use != "power") throw Error(parser + ": option use must be vi or power");
    const Ina219Config cfg = Ina219Config::from_options(merged, parser);

    std::size_t hi = 0;
    while (hi < lines.size() && is_comment(lines[hi].text)) ++hi;
    if (hi == lines.size()) throw Error(parser + ": no header line");
    std::vector<std::string> cols;
    for (auto f : text::split(lines[hi].text, ',')) cols.push_back(text::lower(text::trim(f)));
    auto col = [&](const char* n) {
        const auto it = std::find(cols.begin(), cols.end(), n);
        return it == cols.end() ? -1 : static_cast<int>(it - cols.begin());
    };
    const int ct = col("time_s"), cs = col("shunt"), cb = col("bus"), cc = col("current"), cp = col("power");
    if (ct < 0 || cs < 0 || cb < 0) text::fail(name, lines[hi].number, "header must name time_s, shunt and bus (optional current, power)");
    if (use == "power" && cp < 0) throw Error(parser + ": use=power but the log has no power column");

    // A read returns the last finished shunt+bus cycle (2 tc): it ended between the read and
    // min(poll period, 2 tc) before it (a faster poll sees CNVR=0 until a new cycle ends), and the
    // shunt window's centre is 1.5 tc before that end. time_ref=adc stamps the middle of that
    // range, +- half its width (one conversion time when polling slower than the cycle);
    // time_ref=read keeps the read time, uncertain by the whole lag.
    const double tc = cfg.conversion_time_s();
    std::vector<double> reads;
    for (std::size_t li = hi + 1; li < lines.size() && reads.size() < 100000; ++li)
        if (!is_comment(lines[li].text))
            if (const auto f = text::split(lines[li].text, ','); static_cast<std::size_t>(ct) < f.size())
                if (const auto t = text::to_number(f[ct])) reads.push_back(*t);
    const double poll = median_step(reads);
    const double lag_range = poll > 0 ? std::min(poll, 2 * tc) : 2 * tc;
    const double time_shift = time_ref == "adc" ? 1.5 * tc + 0.5 * lag_range : 0.0;
    const double time_uncertainty = time_ref == "adc" ? 0.5 * lag_range : 1.5 * tc + lag_range;
    TraceBuilder b(name, "ina219-raw");
    b.trace().quantity = use == "power" ? "power register" : (cc >= 0 ? "bus x current register" : "bus x shunt/R");
    std::size_t overflow = 0, first_overflow = 0;
    double max_bus = 0;
    auto reg = [&](std::string_view f, const Line& l, const char* what) -> std::uint16_t {
        f = text::trim(f);
        unsigned long v = 0;
        const bool hex = f.size() > 2 && f[0] == '0' && (f[1] == 'x' || f[1] == 'X');
        const std::string_view digits = hex ? f.substr(2) : f;
        if (digits.empty() || digits.size() > 6) text::fail(name, l.number, std::string(what) + " register '" + std::string(f) + "' is not a 16-bit value");
        for (char ch : digits) {
            int d = -1;
            if (ch >= '0' && ch <= '9') d = ch - '0';
            else if (hex && ch >= 'a' && ch <= 'f') d = ch - 'a' + 10;
            else if (hex && ch >= 'A' && ch <= 'F') d = ch - 'A' + 10;
            if (d < 0) text::fail(name, l.number, std::string(what) + " register '" + std::string(f) + "' is not a number");
            v = v * (hex ? 16 : 10) + d;
        }
        if (v > 0xFFFF) text::fail(name, l.number, std::string(what) + " register '" + std::string(f) + "' exceeds 16 bits");
        return static_cast<std::uint16_t>(v);
    };
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const Line& l = lines[li];
        if (is_comment(l.text)) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != cols.size()) text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields, found " + std::to_string(f.size()));
        const auto t = text::to_number(f[ct]);
        if (!t) text::fail(name, l.number, "time '" + std::string(f[ct]) + "' is not a number");
        Ina219Registers r;
        r.shunt = reg(f[cs], l, "shunt");
        r.bus = reg(f[cb], l, "bus");
        if (cc >= 0) r.current = reg(f[cc], l, "current");
        if (cp >= 0) r.power = reg(f[cp], l, "power");
        if (use != "power") r.power.reset();
        const Ina219Reading d = decode_ina219(r, cfg);
        if (!d.conversion_ready) {
            b.drop(l.number, "no new conversion (CNVR=0)");
            continue;
        }
        if (d.overflow && overflow++ == 0) first_overflow = l.number;
        max_bus = std::max(max_bus, d.bus_v);
        b.add(l.number, *t - time_shift, d.power_w);
    }
    b.trace().time_uncertainty_s = time_uncertainty;
    b.trace().settings = merged;
    b.trace().settings["time_ref"] = time_ref;
    b.trace().settings["use"] = use;
    if (time_shift > 0) {
        char buf[300];
        std::snprintf(buf, sizeof buf, "sample times moved %.4g ms before the read (centre of the shunt ADC window of the last cycle, which ended 0..%.4g ms "
                      "before the read), +- %.4g ms in the error bound; time_ref=read keeps read times", 1e3 * time_shift, 1e3 * lag_range, 1e3 * time_uncertainty);
        b.note(buf);
    }
    if (overflow) b.note(std::to_string(overflow) + " sample(s) flagged overflow (OVF or shunt beyond +-" + std::to_string(cfg.pga_mv) +
                         " mV; first at line " + std::to_string(first_overflow) + "): their power is a lower bound");
    b.trace().resolution_w = use == "power" ? 20 * cfg.current_lsb_a : max_bus * cfg.current_lsb_a;
    PowerTrace tr = b.finish();
    const SamplingReport s = describe_sampling(tr);
    char buf[200];
    std::snprintf(buf, sizeof buf, "conversion cycle %.4g ms (shunt+bus); logged new conversions at %.4g Hz (median), %zu gap(s) > 3x median",
                  2e3 * cfg.conversion_time_s(), s.rate_hz, s.gaps);
    tr.notes.push_back(buf);
    return tr;
}

}  // namespace trn::energy
