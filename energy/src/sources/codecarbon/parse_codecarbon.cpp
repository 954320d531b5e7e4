// CodeCarbon emissions.csv: one row per run (or per project flush) with the run's duration and
// energies in kWh. A per-run summary, never a power trace (trn/energy/run_summaries.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "option_reader.hpp"
#include "text_input.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_summaries.hpp"

namespace trn::energy {
namespace {

constexpr double kJoulesPerKwh = 3.6e6;

// The first non-blank line and its fields (lower case).
std::vector<std::string> header_of(const std::vector<text::Line>& lines, std::size_t& at) {
    at = 0;
    while (at < lines.size() && text::trim(lines[at].text).empty()) ++at;
    std::vector<std::string> cols;
    if (at == lines.size()) return cols;
    for (auto& f : text::split_fields(lines[at].text, ',')) cols.push_back(text::lower(f));
    return cols;
}

}  // namespace

bool looks_like_codecarbon(std::string_view input) {
    std::size_t at = 0;
    const auto cols = header_of(text::split_lines(input.substr(0, std::min<std::size_t>(input.size(), 4096))), at);
    auto has = [&](const char* n) { return std::find(cols.begin(), cols.end(), n) != cols.end(); };
    return has("energy_consumed") && (has("codecarbon_version") || (has("emissions") && has("duration")));
}

double RunSummaries::machine_energy_j(const std::string& machine) const {
    double j = 0;
    for (const auto& r : runs)
        if (r.machine == machine) j += r.energy_j;
    return j;
}

RunSummaries parse_codecarbon_runs(std::string_view input, const std::string& name, const ParseOptions& options) {
    text::check_row_widths(input, name);  // the memory budget before any row is split
    OptionReader o(options, name + " (codecarbon)", {});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    const auto cols = header_of(lines, hi);
    if (cols.empty()) throw Error(name + ": empty file");
    auto col = [&](const char* n) {
        const auto it = std::find(cols.begin(), cols.end(), n);
        return it == cols.end() ? -1 : static_cast<int>(it - cols.begin());
    };
    const int c_energy = col("energy_consumed"), c_duration = col("duration");
    if (c_energy < 0 || c_duration < 0)
        text::fail(name, lines[hi].number, "not a CodeCarbon emissions.csv header (needs energy_consumed and duration columns)");
    const int c_time = col("timestamp"), c_run = col("run_id"), c_project = col("project_name");
    const int c_cpu = col("cpu_energy"), c_gpu = col("gpu_energy"), c_ram = col("ram_energy");
    std::vector<std::pair<std::string, int>> machine_cols;
    for (const char* n : {"hostname", "os", "cpu_model", "cpu_count", "gpu_model", "gpu_count", "ram_total_size", "cloud_provider", "cloud_region"})
        if (col(n) >= 0) machine_cols.push_back({n, col(n)});
    RunSummaries out;
    out.source = name;
    out.format = "codecarbon";
    bool zone_less = false;
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split_fields(l.text, ',');
        if (f.size() == cols.size() && text::lower(f[static_cast<std::size_t>(c_energy)]) == "energy_consumed") continue;  // header repeated (appended runs)
        if (f.size() != cols.size())
            text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields as in the header, found " + std::to_string(f.size()));
        auto number = [&](int c, const char* what, bool required) -> std::optional<double> {
            if (c < 0) return std::nullopt;
            const std::string& v = f[static_cast<std::size_t>(c)];
            if (v.empty() && !required) return std::nullopt;
            const auto n = text::to_number(v);
            if (!n) text::fail(name, l.number, std::string(what) + " '" + v.substr(0, 40) + "' is not a number");
            if (*n < 0) text::fail(name, l.number, std::string(what) + " " + v + " is negative");
            return n;
        };
        RunSummary r;
        r.line = l.number;
        r.energy_j = *number(c_energy, "energy_consumed (kWh)", true) * kJoulesPerKwh;
        r.duration_s = *number(c_duration, "duration (s)", true);
        if (const auto x = number(c_cpu, "cpu_energy (kWh)", false)) r.cpu_j = *x * kJoulesPerKwh;
        if (const auto x = number(c_gpu, "gpu_energy (kWh)", false)) r.gpu_j = *x * kJoulesPerKwh;
        if (const auto x = number(c_ram, "ram_energy (kWh)", false)) r.ram_j = *x * kJoulesPerKwh;
        if (c_run >= 0) r.run_id = f[static_cast<std::size_t>(c_run)];
        if (c_project >= 0) r.project = f[static_cast<std::size_t>(c_project)];
        if (c_time >= 0) {
            r.timestamp = f[static_cast<std::size_t>(c_time)];
            bool known = false;
            r.end_s = text::parse_datetime(r.timestamp, &known);
            if (!r.end_s) text::fail(name, l.number, "timestamp '" + r.timestamp.substr(0, 40) + "' is not an ISO date-time");
            zone_less = zone_less || !known;
        }
        for (const auto& [n, c] : machine_cols)
            if (!f[static_cast<std::size_t>(c)].empty()) r.machine += (r.machine.empty() ? "" : ", ") + n + "=" + f[static_cast<std::size_t>(c)];
        if (r.machine.empty()) r.machine = "(no machine columns)";
        if (std::find(out.machines.begin(), out.machines.end(), r.machine) == out.machines.end()) out.machines.push_back(r.machine);
        // The parts must add up to the total (CodeCarbon writes energy_consumed = cpu + gpu + ram).
        if (r.cpu_j || r.gpu_j || r.ram_j) {
            const double parts = r.cpu_j.value_or(0) + r.gpu_j.value_or(0) + r.ram_j.value_or(0);
            if (std::abs(parts - r.energy_j) > 0.01 * r.energy_j + 1e-6)
                out.notes.push_back("line " + std::to_string(l.number) + ": cpu + gpu + ram energy (" + std::to_string(parts) +
                                    " J) differs from energy_consumed (" + std::to_string(r.energy_j) + " J) by more than 1 %");
        }
        out.runs.push_back(std::move(r));
    }
    if (out.runs.empty()) throw Error(name + ": a CodeCarbon emissions.csv without runs");
    out.notes.push_back("energies in kWh read as J (x 3.6e6); one row per run: the run's total, never interpolated between runs");
    if (zone_less) out.notes.push_back("timestamps have no time zone (CodeCarbon writes the machine's local time)");
    if (out.machines.size() > 1) {
        std::string cols_list;
        for (const auto& [n, c] : machine_cols) cols_list += (cols_list.empty() ? "" : ", ") + n;
        out.notes.push_back(std::to_string(out.machines.size()) + " machines in one file (told apart by " + cols_list +
                            "): totals per machine, never summed across machines");
    }
    return out;
}

RunSummaries read_run_summaries(const std::string& path, const ParseOptions& options) {
    const std::string text = text::read_file(path);
    if (!looks_like_codecarbon(text))
        throw Error(path + ": not a per-run energy summary this reader knows (CodeCarbon emissions.csv); a power trace is read by `energy inspect`");
    return parse_codecarbon_runs(text, path, options);
}

std::string format_run_summaries(const RunSummaries& s) {
    std::ostringstream os;
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s: format %s, %zu run(s) on %zu machine(s)\n", s.source.c_str(), s.format.c_str(), s.runs.size(), s.machines.size());
    os << buf;
    for (std::size_t m = 0; m < s.machines.size(); ++m) {
        os << "  machine " << m + 1 << ": " << s.machines[m] << "\n";
        std::size_t n = 0;
        double seconds = 0;
        for (const auto& r : s.runs) {
            if (r.machine != s.machines[m]) continue;
            ++n, seconds += r.duration_s;
            std::snprintf(buf, sizeof buf, "    line %zu  %s  run %s  %.6g s  %.6g J  (mean %.4g W)\n", r.line, r.timestamp.empty() ? "-" : r.timestamp.c_str(),
                          r.run_id.empty() ? "-" : r.run_id.c_str(), r.duration_s, r.energy_j, r.mean_w());
            os << buf;
        }
        std::snprintf(buf, sizeof buf, "    machine %zu: %zu run(s), %.6g s measured, %.6g J\n", m + 1, n, seconds, s.machine_energy_j(s.machines[m]));
        os << buf;
    }
    for (const auto& n : s.notes) os << "  note: " << n << "\n";
    return os.str();
}

// As a power log: refused, saying what it is and where it is read.
// Options meant for a trace (power=sum, ...) do not change that: it is refused whatever they say.
PowerTrace parse_codecarbon(std::string_view input, const std::string& name, const ParseOptions&) {
    const RunSummaries s = parse_codecarbon_runs(input, name);
    text::fail(name, s.runs.front().line - 1,
               "a CodeCarbon emissions.csv: " + std::to_string(s.runs.size()) + " run(s) on " + std::to_string(s.machines.size()) +
                   " machine(s), one energy total per run (kWh), not a power trace (nothing was measured between runs, so no trace can be "
                   "integrated across them); `trnkit energy runs " + name + "` lists each run's joules");
}

}  // namespace trn::energy
