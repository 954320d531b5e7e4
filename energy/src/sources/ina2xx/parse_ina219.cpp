// INA219 logs: engineering-unit CSV, Arduino Python-tuple lines, and raw registers.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

#include "option_reader.hpp"
#include "series.hpp"
#include "trace_builder.hpp"
#include "trn/energy/ina219.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

using text::Line;
using text::split_fields;
using text::detect_delimiter;

bool is_comment(std::string_view l) {
    l = text::trim(l);
    return l.empty() || l.front() == '#';
}

// "30,3" / "-0,25": a number written with a decimal comma (one comma, digits on both sides).
bool decimal_comma_number(std::string_view f) {
    f = text::trim(f);
    const auto c = f.find(',');
    if (c == std::string_view::npos || f.find(',', c + 1) != std::string_view::npos || f.find('.') != std::string_view::npos) return false;
    std::string dotted(f);
    dotted[c] = '.';
    return c > 0 && c + 1 < f.size() && std::isdigit(static_cast<unsigned char>(f[c - 1])) && std::isdigit(static_cast<unsigned char>(f[c + 1])) &&
           text::to_number(dotted).has_value();
}

// Unit scale read from a column name ("current_mA", "power [W]", "bus(V)", "total_watts").
std::optional<double> unit_scale_from_name(const std::string& name) {
    // "µA" (micro sign or Greek mu) read as "uA"
    const std::string lowered = text::lower(name);
    std::string n;
    for (std::size_t i = 0; i < lowered.size(); ++i) {
        const bool micro = i + 1 < lowered.size() && ((lowered[i] == '\xc2' && lowered[i + 1] == '\xb5') || (lowered[i] == '\xce' && lowered[i + 1] == '\xbc'));
        n += micro ? 'u' : lowered[i];
        i += micro;
    }
    for (const auto& [word, scale] : std::vector<std::pair<std::string, double>>{
             {"milliwatts", 1e-3}, {"milliwatt", 1e-3}, {"kilowatts", 1e3}, {"kilowatt", 1e3}, {"watts", 1}, {"watt", 1}})
        if (n.find(word) != std::string::npos) return scale;
    for (const auto& [suffix, scale] : std::vector<std::pair<std::string, double>>{
             {"mv", 1e-3}, {"uv", 1e-6}, {"ma", 1e-3}, {"ua", 1e-6}, {"mw", 1e-3}, {"uw", 1e-6}, {"kw", 1e3}, {"v", 1}, {"a", 1}, {"w", 1}}) {
        for (const std::string& wrap : {"_" + suffix, "[" + suffix + "]", "(" + suffix + ")", " " + suffix, "/" + suffix})
            if (n.size() >= wrap.size() && n.compare(n.size() - wrap.size(), wrap.size(), wrap) == 0) return scale;
        // a unit in brackets before more text: "power (W) avg"
        for (const std::string& wrap : {"[" + suffix + "]", "(" + suffix + ")"})
            if (n.find(wrap) != std::string::npos) return scale;
    }
    return std::nullopt;
}

double unit_scale(const std::string& unit, const std::string& option, const std::string& parser) {
    static const std::map<std::string, double> scales = {{"v", 1}, {"mv", 1e-3}, {"uv", 1e-6}, {"a", 1}, {"ma", 1e-3},
                                                         {"ua", 1e-6}, {"w", 1}, {"mw", 1e-3}, {"uw", 1e-6}, {"kw", 1e3}};
    const auto it = scales.find(text::lower(unit));
    if (it == scales.end()) throw Error(parser + ": option " + option + "='" + unit + "' is not a unit (V, mV, A, mA, W, mW, kW ...)");
    return it->second;
}

// Joules per unit of an energy counter: uJ (powercap energy_uj), mJ, J, mWh, Wh, kWh.
const std::vector<std::pair<std::string, double>>& energy_units() {
    static const std::vector<std::pair<std::string, double>> units = {{"kwh", 3.6e6}, {"mwh", 3.6}, {"wh", 3600}, {"uj", 1e-6},
                                                                      {"\xc2\xb5j", 1e-6}, {"\xce\xbcj", 1e-6}, {"mj", 1e-3}, {"joules", 1}, {"joule", 1}, {"j", 1}};
    return units;
}

double energy_unit_scale(const std::string& unit, const std::string& parser) {
    for (const auto& [u, scale] : energy_units())
        if (text::lower(unit) == u) return scale;
    throw Error(parser + ": option energy_unit='" + unit + "' is not an energy unit (uJ, mJ, J, mWh, Wh, kWh)");
}

// "energy_uj", "Energy [kWh]", "cumulative_energy_wh", "pkg_joules" -> joules per unit.
std::optional<double> energy_scale_from_name(const std::string& name) {
    const std::string n = text::lower(name);
    for (const auto& [u, scale] : energy_units())
        for (const std::string& wrap : {"_" + u, "[" + u + "]", "(" + u + ")", " " + u, "/" + u})
            if (n.size() >= wrap.size() && (n.compare(n.size() - wrap.size(), wrap.size(), wrap) == 0 ||
                                            ((wrap[0] == '[' || wrap[0] == '(') && n.find(wrap) != std::string::npos)))
                return scale;
    if (n.find("joule") != std::string::npos) return 1.0;
    return std::nullopt;
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
                                     "bus_v_unit", "current_unit", "power_unit", "use", "source", "max_power_w", "energy", "energy_unit",
                                     "max_energy_range_uj", "series", "voltage"});
    const auto lines = text::split_lines(input);
    std::size_t first = 0;
    while (first < lines.size() && is_comment(lines[first].text)) ++first;
    if (first == lines.size()) throw Error(parser + ": no data lines");
    // The line naming the columns: the first non-comment line, unless that is a data row under a
    // '#'-commented header ("# time_s,power_W"), or a preamble (device name, date, settings) comes
    // before the table: then the first line (within 50) that names as many columns as the row
    // after it holds, with a number among them.
    std::string header_text(lines[first].text);
    std::size_t header_at = first;
    std::vector<std::string> layout_notes;
    if (!o.text("columns")) {
        auto names_only = [](std::string_view l) {
            const auto f = split_fields(l, detect_delimiter(l));
            return f.size() >= 2 && std::none_of(f.begin(), f.end(), [](const std::string& x) {
                       return x.empty() || text::to_number(x) || text::parse_datetime(x) || decimal_comma_number(x);
                   });
        };
        auto next_row = [&](std::size_t i) {
            do ++i;
            while (i < lines.size() && is_comment(lines[i].text));
            return i;
        };
        auto heads_table = [&](std::string_view h, std::size_t row) {
            if (row >= lines.size()) return false;
            const char d = detect_delimiter(h);
            auto f = split_fields(lines[row].text, d);
            const std::size_t n = split_fields(h, d).size();
            while (f.size() > n && f.back().empty()) f.pop_back();
            return f.size() == n && std::any_of(f.begin(), f.end(), [](const std::string& x) { return text::to_number(x).has_value(); });
        };
        const bool first_names = names_only(lines[first].text);
        std::size_t comment = first;
        while (comment > 0 && text::trim(lines[comment - 1].text).empty()) --comment;
        std::string commented = comment > 0 ? std::string(text::trim(text::trim(lines[comment - 1].text).substr(1))) : "";
        if (!first_names && comment > 0 && names_only(commented) && heads_table(commented, first)) {
            header_text = commented;
            header_at = comment - 1;
            layout_notes.push_back("header read from the comment line " + std::to_string(lines[header_at].number) + " ('#' before the column names)");
        } else if (!first_names || !heads_table(lines[first].text, next_row(first))) {
            const std::size_t n_first = split_fields(lines[first].text, detect_delimiter(lines[first].text)).size();
            for (std::size_t i = next_row(first), seen = 0; i < lines.size() && seen < 50; i = next_row(i), ++seen)
                if (names_only(lines[i].text) && heads_table(lines[i].text, next_row(i)) &&
                    split_fields(lines[i].text, detect_delimiter(lines[i].text)).size() != n_first) {
                    header_text = std::string(lines[i].text);
                    header_at = i;
                    layout_notes.push_back("skipped the preamble before the header at line " + std::to_string(lines[i].number) + " (lines " +
                                           std::to_string(lines[first].number) + "-" + std::to_string(lines[i].number - 1) + ")");
                    break;
                }
        }
    }
    const char delim = detect_delimiter(header_text);
    const std::string delim_name = delim == ',' ? "','" : delim == ';' ? "';'" : delim == '\t' ? "tab" : "spaces";

    std::vector<std::string> names;
    std::size_t data_start = first;
    if (const auto cols = o.text("columns")) {
        for (auto c : text::split(*cols, ',')) names.emplace_back(text::trim(c));
    } else {
        const auto fields = split_fields(header_text, delim);
        const bool header = std::none_of(fields.begin(), fields.end(), [](const std::string& f) {
            return text::to_number(f) || text::parse_datetime(f) || decimal_comma_number(f);
        });
        if (!header)
            text::fail(name, lines[first].number,
                       "no header row naming the columns; pass columns=... (e.g. columns=index,sensor,bus_V,current_mA,power_W)");
        names = fields;
        data_start = std::max(first, header_at + 1);
    }
    const std::size_t ncols = names.size();

    // Rows as fields. Decimal commas: under ';', tab or spaces a field "30,3" is 30.3 (refused
    // when '.' decimals appear too); under ',' they split every value in two, which is repaired
    // only when every row has exactly twice the header's fields, else refused (never truncated).
    struct Row { std::size_t line; std::vector<std::string> f; };
    std::vector<Row> rows;
    std::size_t comma_fields = 0, dot_fields = 0, first_comma = 0, first_dot = 0;
    bool all_double = true;
    std::size_t first_mismatch = 0, mismatch_count = 0;
    for (std::size_t li = data_start; li < lines.size(); ++li) {
        const Line& l = lines[li];
        if (is_comment(l.text)) continue;
        Row r{l.number, split_fields(l.text, delim)};
        while (r.f.size() > ncols && r.f.back().empty()) r.f.pop_back();  // trailing separators
        // "2024-03-12 10:00:01" split by an aligned-space separator, or "2025-09-08T17:26:50,123456789+08:00"
        // (date --iso-8601=ns) split by a ',' separator: one field again.
        if ((delim == 0 || delim == ',') && r.f.size() == ncols + 1)
            for (std::size_t i = 0; i + 1 < r.f.size(); ++i)
                if (const std::string glue = delim == ',' ? "," : " ";
                    (delim == ',' || !text::parse_datetime(r.f[i])) && text::parse_datetime(r.f[i] + glue + r.f[i + 1])) {
                    r.f[i] += glue + r.f[i + 1];
                    r.f.erase(r.f.begin() + static_cast<std::ptrdiff_t>(i) + 1);
                    break;
                }
        all_double = all_double && r.f.size() == 2 * ncols;
        if (r.f.size() > ncols && mismatch_count++ == 0) first_mismatch = l.number;
        for (const auto& f : r.f) {
            if (decimal_comma_number(f) && comma_fields++ == 0) first_comma = l.number;
            else if (f.find('.') != std::string::npos && text::to_number(f) && dot_fields++ == 0) first_dot = l.number;
        }
        rows.push_back(std::move(r));
    }
    bool decimal_commas = false;
    if (mismatch_count) {
        if (delim == ',' && all_double && !rows.empty()) {
            for (auto& r : rows) {
                std::vector<std::string> joined;
                for (std::size_t i = 0; i < ncols; ++i) joined.push_back(r.f[2 * i] + "." + r.f[2 * i + 1]);
                r.f = std::move(joined);
            }
            decimal_commas = true;
        } else {
            const Row& bad = *std::find_if(rows.begin(), rows.end(), [&](const Row& r) { return r.line == first_mismatch; });
            text::fail(name, first_mismatch,
                       std::to_string(bad.f.size()) + " fields, but the header names " + std::to_string(ncols) + " (separator " + delim_name +
                           ")" + (delim == ',' ? ": decimal commas under a ',' separator (a comma-decimal locale)? re-export with ';' as the separator or '.' decimals"
                                               : ": columns= names them"));
        }
    } else if (comma_fields) {
        if (delim == ',')
            text::fail(name, first_comma, "a quoted number with a decimal comma under a ',' separator; re-export with '.' decimals or ';' as the separator");
        if (dot_fields)
            text::fail(name, std::max(first_comma, first_dot),
                       "numbers with decimal commas (line " + std::to_string(first_comma) + ") and with decimal points (line " + std::to_string(first_dot) +
                           "): one locale per file");
        for (auto& r : rows)
            for (auto& f : r.f)
                if (decimal_comma_number(f)) f[f.find(',')] = '.';
        decimal_commas = true;
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
    auto energy_like = [&](const std::string& n) { return has(n, "energy") || has(n, "wh") || has(n, "joule") || has(n, "cumulative"); };
    auto power_like = [&](const std::string& n) {
        if (energy_like(n)) return false;
        const bool gpu_n = n.size() >= 4 && n.compare(0, 3, "gpu") == 0 && std::isdigit(static_cast<unsigned char>(n[3]));
        return has(n, "power") || has(n, "watt") || has(n, "leistung") || n == "p" || n == "w" || n == "mw" || gpu_n;
    };
    Column time = find("time", [&](const std::string& n) {
        return has(n, "time") || n == "t" || has(n, "elapsed") || n == "index" || n == "idx" || has(n, "zeit");
    });
    if (time.index < 0) time = find("time", [&](const std::string& n) { return n == "date" || n == "datum"; });
    // A separate date column before a time-of-day one ("Date;Time;Power [W]").
    int date_col = -1;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (static_cast<int>(i) != time.index && (text::lower(names[i]) == "date" || text::lower(names[i]) == "datum")) date_col = static_cast<int>(i);
    Column shunt = find("shunt_v", [&](const std::string& n) { return has(n, "shunt"); });
    std::vector<Column> powers;
    const std::string power_option = o.text("power", "");
    if (!power_option.empty() && power_option != "sum") {
        powers.push_back(find("power", [](const std::string&) { return false; }));
    } else {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (static_cast<int>(i) != time.index && power_like(text::lower(names[i]))) powers.push_back({static_cast<int>(i), 1, names[i]});
    }
    Column current = find("current", [&](const std::string& n) {
        return (has(n, "current") || has(n, "strom") || n == "i" || n == "ma" || n == "a" || n == "i_ma" || n == "current_ma") && !has(n, "shunt");
    });
    Column bus = find("bus_v", [&](const std::string& n) {
        return (has(n, "bus") || has(n, "volt") || has(n, "spannung") || n == "v" || n == "u" || n == "v_bus") && !has(n, "shunt");
    });
    if (time.index < 0) throw Error(parser + ": no time column among '" + header_text.substr(0, 200) + "'; pass time=NAME");
    const std::string use = o.text("use", "vi");
    if (use != "vi" && use != "power") throw Error(parser + ": option use must be vi or power");
    // A cumulative energy column (energy_uj, J, mWh, kWh) is read as a counter: its differences
    // over time are the power. Taken when named (energy=) or when there is nothing else to read.
    Column energy;
    if (o.text("energy")) {
        energy = find("energy", [](const std::string&) { return false; });
        powers.clear();
    } else if (!(bus.index >= 0 && current.index >= 0) && powers.empty()) {
        std::vector<Column> energies;
        for (std::size_t i = 0; i < names.size(); ++i)
            if (static_cast<int>(i) != time.index && energy_like(text::lower(names[i]))) energies.push_back({static_cast<int>(i), 1, names[i]});
        if (energies.size() > 1) {
            std::string list;
            for (const auto& e : energies) list += (list.empty() ? "'" : ", '") + e.name + "'";
            throw Error(parser + ": " + std::to_string(energies.size()) + " energy columns (" + list +
                        ") and no power column: pass energy=NAME for the cumulative counter to read; none is picked silently");
        }
        if (!energies.empty()) energy = energies.front();
    }
    const bool counter = energy.index >= 0;
    const bool vi = !counter && bus.index >= 0 && current.index >= 0 && !(use == "power" && !powers.empty());
    // A current-only export (Nordic PPK2, Otii, Joulescope with only current): power is the current
    // times the supply voltage the user states; never assumed.
    const bool current_only = !vi && !counter && powers.empty() && current.index >= 0 && bus.index < 0;
    const auto supply_v = o.number("voltage");
    if (supply_v && !current_only)
        throw Error(parser + ": option voltage= is for a current-only log (a current column, no bus voltage, power or energy column); this log has " +
                    (vi ? "bus voltage and current" : counter ? "an energy counter" : "a power column"));
    if (supply_v && !(*supply_v > 0 && *supply_v < 1000)) throw Error(parser + ": option voltage must be a supply voltage in (0, 1000) V");
    if (current_only && !supply_v)
        throw Error(parser + ": a current-only log (column '" + current.name +
                    "', no voltage or power: a PPK2, Otii or Joulescope current export): energy needs the supply voltage; pass voltage=V (the source "
                    "voltage the device ran at)");
    if (!vi && !counter && !current_only && powers.empty())
        throw Error(parser + ": needs a power column, bus voltage and current columns, or a cumulative energy column (energy_uj, energy_J, ..._kWh)");
    if (counter) {
        if (const auto u = o.text("energy_unit")) energy.scale = energy_unit_scale(*u, parser);
        else if (const auto sc = energy_scale_from_name(energy.name)) energy.scale = *sc;
        else
            throw Error(parser + ": energy column '" + energy.name + "' has no unit in its name (uJ? J? Wh? kWh?); pass energy_unit=uJ, mJ, J, mWh, Wh or kWh");
    }
    if (!vi && !counter && powers.size() > 1 && power_option != "sum") {
        std::string list;
        for (const auto& p : powers) list += (list.empty() ? "'" : ", '") + p.name + "'";
        throw Error(parser + ": " + std::to_string(powers.size()) + " power columns (" + list +
                    "): pass power=NAME for one of them or power=sum for their sum; none is picked silently");
    }
    if (vi || counter || power_option != "sum") powers.resize(1);

    auto number_at = [&](const Row& r, const Column& c) -> std::optional<double> {
        if (c.index < 0 || static_cast<std::size_t>(c.index) >= r.f.size()) return std::nullopt;
        return text::to_number(r.f[c.index]);
    };
    auto median_of = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    std::vector<std::string> unit_notes;
    // Units: from the option, else the column name; never a silent default.
    auto scale_of = [&](Column& c, const std::string& unit_option) -> bool {
        if (c.index < 0) return true;
        if (const auto u = o.text(unit_option)) c.scale = unit_scale(*u, unit_option, parser);
        else if (const auto s = unit_scale_from_name(c.name)) c.scale = *s;
        else return false;
        return true;
    };
    if (!scale_of(bus, "bus_v_unit")) {
        std::vector<double> v;
        for (const auto& r : rows)
            if (const auto x = number_at(r, bus)) v.push_back(std::abs(*x));
        const double top = v.empty() ? 0 : *std::max_element(v.begin(), v.end());
        if (top > 60)
            throw Error(parser + ": bus voltage column '" + bus.name + "' has no unit in its name and reaches " + std::to_string(top) +
                        " (mV? no INA bus reaches 60 V); pass bus_v_unit=V or mV");
        unit_notes.push_back("bus voltage column '" + bus.name + "' has no unit in its name: V (its values stay within 60)");
    }
    bool current_known = scale_of(current, "current_unit");
    for (auto& p : powers) {
        if (scale_of(p, "power_unit")) continue;
        // Unit from the ratio to V x I where both exist (current in a known unit).
        if (bus.index >= 0 && current.index >= 0 && current_known) {
            std::vector<double> ratio;
            for (const auto& r : rows) {
                const auto v = number_at(r, bus), i = number_at(r, current), w = number_at(r, p);
                if (v && i && w && std::abs(*v * bus.scale * *i * current.scale) > 1e-3) ratio.push_back(*w / (*v * bus.scale * *i * current.scale));
            }
            const double m = median_of(ratio);
            for (const auto& [unit, scale] : std::vector<std::pair<const char*, double>>{{"W", 1}, {"mW", 1e-3}, {"kW", 1e3}})
                if (m * scale > 0.8 && m * scale < 1.25) {
                    p.scale = scale;
                    char buf[200];
                    std::snprintf(buf, sizeof buf, "power column '%s' has no unit in its name: %s, from its ratio to V x I (median %.4g)", p.name.c_str(), unit, m);
                    unit_notes.push_back(buf);
                    break;
                }
            if (p.scale != 1 || (m > 0.8 && m < 1.25)) continue;
        }
        if (vi) { p.index = -1; continue; }  // only a cross-check; V x I is integrated
        throw Error(parser + ": power column '" + p.name + "' has no unit in its name (W? mW?); pass power_unit=W, mW or kW");
    }
    if (!current_known) {
        if (!powers.empty() && powers[0].index >= 0 && (o.text("power_unit") || unit_scale_from_name(powers[0].name)) && bus.index >= 0) {
            std::vector<double> ratio;
            for (const auto& r : rows) {
                const auto v = number_at(r, bus), i = number_at(r, current), w = number_at(r, powers[0]);
                if (v && i && w && std::abs(*w * powers[0].scale) > 1e-3) ratio.push_back(*v * bus.scale * *i / (*w * powers[0].scale));
            }
            const double m = median_of(ratio);
            for (const auto& [unit, scale] : std::vector<std::pair<const char*, double>>{{"A", 1}, {"mA", 1e-3}})
                if (m * scale > 0.8 && m * scale < 1.25) {
                    current.scale = scale, current_known = true;
                    char buf[200];
                    std::snprintf(buf, sizeof buf, "current column '%s' has no unit in its name: %s, from V x I against power column '%s' (median ratio %.4g)",
                                  current.name.c_str(), unit, powers[0].name.c_str(), m);
                    unit_notes.push_back(buf);
                }
        }
        if (!current_known && (vi || current_only))
            throw Error(parser + ": current column '" + current.name + "' has no unit in its name (A? mA? uA?); pass current_unit=A, mA or uA");
    }

    std::string time_unit = o.text("time_unit", "");
    const std::string tname = text::lower(time.name);
    if (time_unit.empty()) {
        if (tname == "index" || tname == "idx") time_unit = "index";
        else if (has(tname, "_ms") || has(tname, "[ms]") || has(tname, "(ms)")) time_unit = "ms";
        else if (has(tname, "_us") || has(tname, "[us]") || has(tname, "(us)")) time_unit = "us";
        else time_unit = "auto";  // seconds or ISO date, decided by the first row
    }
    const double period = o.number("period_s", 0);
    if (time_unit == "index" && !(period > 0)) throw Error(parser + ": time column '" + time.name + "' is a row index; pass period_s=SECONDS");

    TraceBuilder b(name, "ina219-csv");
    std::vector<double> bus_values;
    if (vi)
        for (const auto& r : rows)
            if (const auto v = number_at(r, bus)) bus_values.push_back(std::abs(*v * bus.scale));
    // A USB meter's export names the data lines' voltages (D+, D-, Data+ (V), ...): a USB device.
    const bool usb_meter = std::any_of(names.begin(), names.end(), [](const std::string& n) {
        const std::string l = text::lower(n);
        return l.rfind("d+", 0) == 0 || l.rfind("d-", 0) == 0 || l.rfind("data+", 0) == 0 || l.rfind("data-", 0) == 0;
    });
    const std::string source = o.text("source", usb_meter ? "usb" : (vi && median_of(bus_values) <= 60) || current_only ? "rail" : "node");
    b.power_source(source, o);
    if (!vi && !counter && !o.text("power_unit"))
        for (const auto& p : powers) {
            if (p.index < 0 || !unit_scale_from_name(p.name)) continue;
            std::vector<double> raw;
            for (const auto& r : rows)
                if (const auto x = number_at(r, p)) raw.push_back(*x);
            check_power_unit_against_source(name, p.name, p.scale, raw, b.power_source(), "power_unit");
        }
    for (auto& n : layout_notes) b.note(std::move(n));
    for (auto& n : unit_notes) b.note(std::move(n));
    if (decimal_commas)
        b.note(delim == ',' ? "decimal commas under a ',' separator: every row has twice the header's fields, read as value pairs 'int,frac'"
                            : "decimal commas (a comma-decimal locale, separator " + delim_name + ") read as decimal points");
    std::string quantity;
    if (counter) quantity = energy.name + " (cumulative energy counter; power = its differences over time)";
    else if (vi) quantity = bus.name + "*" + current.name;
    else if (current_only) quantity = current.name + " x voltage=" + o.text("voltage", "") + " V";
    else
        for (const auto& p : powers) quantity += (quantity.empty() ? "" : "+") + p.name;
    b.trace().quantity = quantity;
    // Key columns of a long-form log (one row per device x domain x time): the columns read for
    // nothing else whose values tell series apart, and any column series= names.
    std::vector<int> key_cols;
    {
        std::set<int> used = {time.index, date_col, shunt.index, bus.index, current.index, energy.index};
        for (const auto& p : powers) used.insert(p.index);
        std::set<std::string> named;
        if (const auto sel = o.text("series"); sel && *sel != "all") {
            // Named, not a temporary inside the range expression: split's views point into it, and
            // before C++23 a temporary there dies before the loop body runs (ASan: use after free).
            const std::string clauses = sel->rfind("sum:", 0) == 0 ? sel->substr(4) : *sel;
            for (auto clause : text::split(clauses, ','))
                named.insert(text::lower(text::trim(clause.substr(0, clause.find('=')))));
        }
        for (std::size_t i = 0; i < ncols; ++i) {
            if (used.count(static_cast<int>(i))) continue;
            std::vector<std::string> values;
            for (const auto& r : rows)
                if (i < r.f.size()) values.push_back(r.f[i]);
            if (named.count(text::lower(names[i])) || series::is_key_column(names[i], values)) key_cols.push_back(static_cast<int>(i));
        }
    }
    std::vector<series::Key> series_keys;
    auto series_of = [&](const Row& r) {
        series::Key k;
        for (int c : key_cols) k.push_back({names[c], static_cast<std::size_t>(c) < r.f.size() ? r.f[c] : ""});
        const auto it = std::find(series_keys.begin(), series_keys.end(), k);
        if (it != series_keys.end()) return static_cast<std::size_t>(it - series_keys.begin());
        series_keys.push_back(std::move(k));
        return series_keys.size() - 1;
    };
    std::vector<series::Sample> samples;
    std::size_t bad = 0, first_bad = 0;
    std::vector<double> vi_ratio;
    std::optional<bool> zoned;  // date-time stamps: all with a UTC offset, or none (a mix is refused)
    auto stamp = [&](const std::string& tf, std::size_t line) -> std::optional<double> {
        bool known = false;
        const auto d = text::parse_datetime(tf, &known);
        if (!d) return d;
        if (zoned && *zoned != known)
            text::fail(name, line, "time stamp '" + tf.substr(0, 40) + "' " + (known ? "carries a UTC offset" : "has no time zone") + " while the rows before it " +
                                       (known ? "have none" : "carry one") + ": one kind of stamp per log");
        zoned = known;
        b.trace().wall_clock = true;
        return d;
    };
    for (const Row& r : rows) {
        const auto& f = r.f;
        auto get = [&](const Column& c) -> std::optional<double> {
            const auto v = number_at(r, c);
            return v ? std::optional<double>(*v * c.scale) : std::nullopt;
        };
        std::optional<double> t;
        if (static_cast<std::size_t>(time.index) < f.size()) {
            std::string tf = f[time.index];
            if (date_col >= 0 && static_cast<std::size_t>(date_col) < f.size() && !text::parse_datetime(tf) && !text::to_number(tf))
                tf = f[date_col] + " " + tf;
            if (time_unit == "auto") {
                if (auto n = text::to_number(tf)) t = n;
                else if (auto d = stamp(tf, r.line)) t = d;
            } else if (time_unit == "iso") {
                if (auto d = stamp(tf, r.line)) t = d;
            } else if (auto n = text::to_number(tf)) {
                t = time_unit == "ms" ? *n * 1e-3 : time_unit == "us" ? *n * 1e-6 : time_unit == "index" ? *n * period : *n;
            }
        }
        std::optional<double> w;
        if (counter) {
            w = get(energy);  // joules so far
        } else if (current_only) {
            if (const auto i = get(current)) w = *i * *supply_v;
        } else if (vi) {
            const auto v = get(bus), i = get(current);
            if (v && i) w = *v * *i;
            if (const auto p = get(powers[0]); w && p && std::abs(*w) > 1e-3) vi_ratio.push_back(*p / *w);
        } else {
            double sum = 0;
            bool ok = true;
            for (const auto& p : powers) {
                const auto x = get(p);
                ok = ok && x.has_value();
                if (x) sum += *x;
            }
            if (ok) w = sum;
        }
        if (!t || !w) {
            if (bad++ == 0) first_bad = r.line;
            b.drop(r.line, counter ? "missing or unreadable time/energy fields" : "missing or unreadable time/power fields");
            continue;
        }
        samples.push_back({r.line, *t, *w, series_of(r)});
    }
    if (bad * 2 > rows.size() && bad > 0)
        text::fail(name, first_bad, "most rows are unreadable (" + std::to_string(bad) + "); check columns/delimiter");
    if (series_keys.size() > 1 && !o.text("series") && !series::interleaved(samples)) {  // labels in blocks: one trace
        for (auto& x : samples) x.series = 0;
        series_keys = {series::Key{}};
    }
    const series::Selection sel = series::select(series_keys, o.text("series"), parser, "rows");
    if (series_keys.size() > 1 || o.text("series"))
        b.note(std::string(sel.sum ? "power is the sum of series " : "series ") + sel.described + " (series=" + o.text("series", "") + ") of " +
               std::to_string(series_keys.size()) + " in this long-form log" + (sel.sum ? ", per poll at its first row's time" : ""));
    if (sel.sum) b.trace().quantity = "sum of " + b.trace().quantity + " over " + sel.described;
    else if (series_keys.size() > 1) b.trace().quantity += " of " + sel.described;
    std::vector<series::Sample> out;
    for (const auto& x : samples)
        if (sel.chosen[x.series]) out.push_back(x);
    if (counter) {
        const double range_uj = o.number("max_energy_range_uj", 0);
        if (o.text("max_energy_range_uj") && !(range_uj > 0)) throw Error(parser + ": option max_energy_range_uj must be > 0");
        std::vector<std::optional<double>> start;
        std::size_t wraps = 0;
        out = series::counter_to_power(out, series_keys.size(), range_uj * 1e-6, name, energy.name, start, wraps, b);
        if (!o.text("energy_unit")) {  // a unit read from the header is tested against the source
            std::vector<double> w;
            for (const auto& x : out) w.push_back(x.v);
            check_energy_unit_against_source(name, energy.name, energy.scale, w, b.power_source());
        }
        b.trace().kind = SampleKind::IntervalMean;
        for (const auto& st : start)
            if (st && (!b.trace().first_interval_start || *st < *b.trace().first_interval_start)) b.trace().first_interval_start = st;
        b.note("energy counter '" + energy.name + "' read as differences: each reading's power is the mean over the interval since the one before "
               "(the first reading starts the first interval); whole-log joules are the counter's rise");
        if (wraps) b.note(std::to_string(wraps) + " counter wrap(s) unwrapped at max_energy_range_uj=" + o.text("max_energy_range_uj", ""));
    }
    if (sel.sum) out = series::sum_per_poll(out, sel.chosen, name, b);
    for (const auto& x : out) b.add(x.line, x.t, x.v);
    if (!vi_ratio.empty()) {
        std::nth_element(vi_ratio.begin(), vi_ratio.begin() + vi_ratio.size() / 2, vi_ratio.end());
        const double r = vi_ratio[vi_ratio.size() / 2];
        if (r < 0.5 || r > 2) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "power column '%s' is %.4g x bus*current (median): a logger unit bug? using V*I", powers[0].name.c_str(), r);
            b.note(buf);
        }
    }
    if (powers.size() > 1) b.note("power is the sum of " + std::to_string(powers.size()) + " columns (power=sum): " + quantity);
    b.trace().local_time = b.trace().wall_clock && !zoned.value_or(true);
    if (b.trace().local_time) b.note("time stamps have no time zone; taken as UTC (timezone= / utc_offset= to convert)");
    if (!b.trace().w.empty() && *std::min_element(b.trace().w.begin(), b.trace().w.end()) < 0)
        b.note("negative power readings present (shunt offset or reverse current); kept as read");
    return b.finish();
}

PowerTrace parse_ina219_tuples(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (ina219-tuples)";
    OptionReader o(options, parser, {"tick_period_s", "tick_bits", "max_bus_v", "max_power_w"});
    const double tick = o.number("tick_period_s", 0);
    const double bits = o.number("tick_bits", 16);
    if (bits < 8 || bits > 32 || bits != std::trunc(bits)) throw Error(parser + ": tick_bits must be an integer 8..32");
    const double wrap = std::ldexp(1.0, static_cast<int>(bits));
    const double max_bus = o.number("max_bus_v", 16);
    TraceBuilder b(name, "ina219-tuples");
    b.power_source("rail", o);
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
    ParseOptions cap;
    for (const auto& [k, v] : options) {
        if (k == "time_ref") time_ref = v;
        else if (k == "max_power_w") cap[k] = v;
        else merged[k] = v;
    }
    const OptionReader cap_reader(cap, parser, {"max_power_w"});
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
    // Each read's own lag: the cycle it returns ended after the previous read (else CNVR=0) and
    // at most one cycle before it, uniformly over min(this read's interval, 2 tc) for a chip
    // running free of the logger's clock. Its stamp is the middle of that range, its SD range/sqrt(12).
    double prev_read = -1, sum_var = 0, lag_sum = 0;
    std::size_t kept = 0;
    TraceBuilder b(name, "ina219-raw");
    b.power_source("rail", cap_reader);
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
        const double dt = prev_read >= 0 && *t > prev_read ? *t - prev_read : (poll > 0 ? poll : 2 * tc);
        prev_read = *t;
        if (!d.conversion_ready) {
            b.drop(l.number, "no new conversion (CNVR=0)");
            continue;
        }
        const double range = std::min(dt, 2 * tc);
        if (d.overflow && overflow++ == 0) first_overflow = l.number;
        max_bus = std::max(max_bus, d.bus_v);
        if (time_ref == "adc") {
            b.add(l.number, *t - 1.5 * tc - 0.5 * range, d.power_w);
            sum_var += range * range / 12, lag_sum += range, ++kept;
        } else {
            b.add(l.number, *t, d.power_w);
        }
    }
    b.trace().time_uncertainty_s = time_uncertainty;
    if (kept) b.trace().time_sd_s = std::sqrt(sum_var / static_cast<double>(kept));
    b.trace().settings = merged;
    b.trace().settings["time_ref"] = time_ref;
    b.trace().settings["use"] = use;
    if (time_shift > 0) {
        char buf[500];
        std::snprintf(buf, sizeof buf, "sample times moved %.4g ms before the read on average (centre of the shunt ADC window of the last cycle, which "
                      "ended 0..min(read interval, %.4g ms) before the read); timing error SD %.4g ms from the measured read intervals, a 95 %% term in "
                      "the error bound; time_ref=read keeps read times", 1e3 * (1.5 * tc + 0.5 * (kept ? lag_sum / static_cast<double>(kept) : lag_range)),
                      2e3 * tc, 1e3 * b.trace().time_sd_s);
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
