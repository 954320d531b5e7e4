// Format names, recognition of a log from its text, and reading a log file.

#include <algorithm>
#include <optional>

#include "text_input.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_summaries.hpp"
#include "trn/energy/time_zone.hpp"

namespace trn::energy {

ParseOptions parse_option_list(const std::vector<std::string>& items) {
    ParseOptions o;
    for (const auto& item : items) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0) throw Error("parser option '" + item + "': expected KEY=VALUE");
        o[item.substr(0, eq)] = item.substr(eq + 1);
    }
    return o;
}

std::vector<std::string> power_log_formats() {
    return {
#define TRN_POWER_FORMAT(name, parser, ...) name,
#include "power_formats.def"
#undef TRN_POWER_FORMAT
    };
}

namespace {

// A --format=csv,noheader row: comma-separated, one field an nvidia-smi time stamp
// "YYYY/MM/DD HH:MM:SS.mmm" (slashes: ISO dates with '-' belong to other loggers).
bool looks_like_headerless_nvidia_smi(std::string_view l) {
    const auto fields = text::split(l, ',');
    if (fields.size() < 2) return false;
    for (auto f : fields) {
        const auto v = text::trim(f);
        if (v.size() >= 19 && v[4] == '/' && v[7] == '/' && text::parse_datetime(v)) return true;
    }
    return false;
}

}  // namespace

std::string detect_power_log_format(std::string_view input, const std::string& name) {
    const auto lines = text::split_lines(input);
    std::size_t first = 0;
    while (first < lines.size() && text::trim(lines[first].text).empty()) ++first;
    if (first == lines.size()) throw Error(name + ": empty file");
    const std::string_view l = text::trim(lines[first].text);
    if (text::starts_with(l, "# trnkit-power")) return "trnkit";
    if (text::starts_with(l, "# SIMULATED INA219")) return "ina219-raw";
    if (looks_like_codecarbon(input)) return "codecarbon";
    if (looks_like_scaphandre(input)) return "scaphandre";
    if (looks_like_jtop(l)) return "jtop";
    if (looks_like_pi_pmic(input)) return "pi5-pmic";
    if (looks_like_json(input))
        text::fail(name, lines[first].number, std::string("a JSON document") + (l.front() == '{' && lines.size() > first + 1 ? " (JSON Lines: one object per line)" : "") +
                                                  ", not a CSV or text power log; the JSON read here is Scaphandre's (format scaphandre); "
                                                  "for another tool's JSON, export a CSV with a time and a power column");
    for (const auto& line : lines) {  // a raw register header after comments
        const auto s = text::trim(line.text);
        if (s.empty() || s.front() == '#') continue;
        if (text::lower(s).rfind("time_s,shunt,bus", 0) == 0) return "ina219-raw";
        break;
    }
    if (l.find("power.draw") != std::string_view::npos) return "nvidia-smi";  // with or without a timestamp column
    if (looks_like_headerless_nvidia_smi(l)) return "nvidia-smi";
    if (text::starts_with(l, "timestamp ") && l.find(',') == std::string_view::npos) return "pmt";
    if (l.front() == '(') return "ina219-tuples";
    if (text::starts_with(l, "Timestamp:")) return "hwmon-records";
    if (text::starts_with(text::lower(l), "date,cpu utilization")) return "powerjoular";
    if (text::starts_with(l, "turbostat version")) return "turbostat";
    const std::size_t probe = std::min<std::size_t>(lines.size(), 400);
    for (std::size_t i = first; i < probe; ++i) {
        const auto s = lines[i].text;
        if (i < first + 50 && s.find("RAM ") != std::string_view::npos &&
            (s.find("VDD_") != std::string_view::npos || s.find("POM_") != std::string_view::npos || s.find("VIN_") != std::string_view::npos))
            return "tegrastats";
        // perf stat -x: a row "time,value,Joules,event" (a CSV whose header names a Joules column is not one)
        if (i < first + 50 && (s.find(",Joules,") != std::string_view::npos || s.find(";Joules;") != std::string_view::npos)) {
            const auto f = text::split(text::trim(s), s.find(",Joules,") != std::string_view::npos ? ',' : ';');
            if (f.size() >= 4 && text::to_number(f[0]) && text::trim(f[2]) == "Joules") return "perf-stat";
        }
        const auto tok = text::split_ws(s);
        if (i < first + 50 && tok.size() >= 4 && text::to_number(tok[0]) && tok[2] == "Joules") return "perf-stat";  // perf stat -I text
        if (i < first + 50 && !tok.empty() && tok.front() == "Time" && std::find(tok.begin(), tok.end(), "Watts") != tok.end()) return "powerstat";
        for (auto t : tok)
            if (t == "PkgWatt" || t == "CorWatt" || t == "RAMWatt" || t == "SysWatt") return "turbostat";
    }
    for (const auto& line : lines)
        if (text::starts_with(text::trim(line.text), "Total Energy:"))
            text::fail(name, line.number, "a rapl-tools summary (power.log), not a power trace; it holds only the run's total energy");
    if (l.find("----vbat") != std::string_view::npos || l.find("vin:") != std::string_view::npos)
        text::fail(name, lines[first].number, "free-text charger log with no time stamps: no power trace can be built from it");
    if (looks_like_likwid_timeline(input)) return "likwid-timeline";
    const auto fields = text::split(l, ',');
    bool all_numbers = fields.size() == 5;
    for (auto f : fields) all_numbers = all_numbers && text::to_number(f).has_value();
    if (all_numbers) return "rapl-tools";
    // A logger CSV: ',', ';' or tab separated, or a space-aligned table whose next line has about
    // as many fields and a number.
    for (char sep : {',', ';', '\t'})
        if (text::split(l, sep).size() >= 2) return "ina219-csv";
    // the same after '#' comment lines (a commented header or a logger's remarks)
    for (const auto& line : lines) {
        const auto c = text::trim(line.text);
        if (c.empty() || c.front() == '#') continue;
        for (char sep : {',', ';', '\t'})
            if (text::split(c, sep).size() >= 2 && l.front() == '#') return "ina219-csv";
        break;
    }
    const auto head = text::split_ws(l);
    std::size_t next = first + 1;
    while (next < lines.size() && (text::trim(lines[next].text).empty() || text::trim(lines[next].text).front() == '#')) ++next;
    if (head.size() >= 2 && next < lines.size()) {
        const auto row = text::split_ws(lines[next].text);
        const bool numeric = std::any_of(row.begin(), row.end(), [](std::string_view v) { return text::to_number(v).has_value(); });
        if (numeric && (row.size() == head.size() || row.size() == head.size() + 1)) return "ina219-csv";
    }
    // A preamble (device name, date, settings) before a CSV table: a line naming columns under ',',
    // ';' or tab, followed by a row with as many fields and a number.
    for (std::size_t i = first + 1; i < std::min<std::size_t>(lines.size(), first + 50); ++i) {
        const char d = text::detect_delimiter(lines[i].text);
        if (d == 0) continue;
        const auto h = text::split_fields(lines[i].text, d);
        if (h.size() < 2 || std::any_of(h.begin(), h.end(), [](const std::string& x) { return x.empty() || text::to_number(x); })) continue;
        std::size_t r = i + 1;
        while (r < lines.size() && (text::trim(lines[r].text).empty() || text::trim(lines[r].text).front() == '#')) ++r;
        if (r == lines.size()) break;
        const auto row = text::split_fields(lines[r].text, d);
        if (row.size() == h.size() && std::any_of(row.begin(), row.end(), [](const std::string& x) { return text::to_number(x).has_value(); }))
            return "ina219-csv";
    }
    text::fail(name, lines[first].number, "unrecognised power log (first line '" + std::string(l.substr(0, 80)) +
                                              "'); name its format (one of trnkit energy formats)");
}

namespace {

PowerTrace parse_in_format(std::string_view input, const std::string& name, const std::string& format, const ParseOptions& options) {
    const std::string f = format == "auto" ? detect_power_log_format(input, name) : format;
#define TRN_POWER_FORMAT(format_name, parser, ...) \
    if (f == format_name) return parser(input, name, options);
#include "power_formats.def"
#undef TRN_POWER_FORMAT
    std::string list;
    for (const auto& n : power_log_formats()) list += (list.empty() ? "" : ", ") + n;
    throw Error("power log format '" + format + "': unknown (known: auto, " + list + ")");
}

}  // namespace

// timezone= / utc_offset= apply to every format with local stamps, and time_uncertainty_s= to
// any log whose logger says how late or early its stamps can be (an INA3221 read through hwmon
// returns the last of its conversions: give its conversion time); so they are taken here.
PowerTrace parse_power_log(std::string_view input, const std::string& name, const std::string& format, const ParseOptions& options) {
    ParseOptions rest = options;
    const auto zone = take_time_zone(rest);
    std::optional<double> uncertainty;
    if (const auto it = rest.find("time_uncertainty_s"); it != rest.end()) {
        uncertainty = text::to_number(it->second);
        if (!uncertainty || *uncertainty < 0 || *uncertainty > 10)
            throw Error(name + ": option time_uncertainty_s='" + it->second + "' must be a number of seconds in [0, 10]");
        rest.erase(it);
    }
    // The memory budget before anything splits a row (JSON is parsed whole, never split in fields).
    if (!(format == "scaphandre" || (format == "auto" && looks_like_json(input)))) text::check_row_widths(input, name);
    PowerTrace tr = parse_in_format(input, name, format, rest);
    if (zone) apply_time_zone(tr, *zone);
    if (uncertainty) {
        tr.time_uncertainty_s = *uncertainty;
        tr.time_sd_s = 0;  // a stated worst case replaces the parser's measured spread
        tr.settings["time_uncertainty_s"] = options.at("time_uncertainty_s");
        tr.notes.push_back("sample times uncertain by +-" + options.at("time_uncertainty_s") + " s (time_uncertainty_s): included in the error bounds");
    }
    return tr;
}

// Read with a size limit: a device such as /dev/zero given as a log must not fill the memory.
PowerTrace read_power_log(const std::string& path, const std::string& format, const ParseOptions& options) {
    return parse_power_log(text::read_file(path), path, format, options);
}

}  // namespace trn::energy
