#pragma once
// Readers for the power logs people actually have. Each takes the file's text and a name for
// messages, returns a PowerTrace in watts and seconds, and throws trn::Error naming
// "name:line: why" for anything it cannot read. Options are "key=value" pairs (see ENERGY.md);
// an unknown key is an error, so a typo never silently falls back to a default.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

using ParseOptions = std::map<std::string, std::string>;

// "key=value" strings (from the CLI) to options; throws on a missing '='.
ParseOptions parse_option_list(const std::vector<std::string>& items);

// Logger CSVs (INA219/INA22x scripts, wall meters, BMC or pynvml loggers): ',', ';', tab or
// space-aligned, with a header naming columns, or headerless with columns=... . Units from the
// column names or options, never assumed; decimal commas read where unambiguous, else refused. Options: columns (comma list overriding the header), time, bus_v, shunt_v,
// current, power (column names), time_unit (s|ms|us|iso|index), period_s (for time_unit=index),
// bus_v_unit/shunt_v_unit (V|mV), current_unit (A|mA), power_unit (W|mW), use (vi|power).
PowerTrace parse_ina219_csv(std::string_view text, const std::string& name, const ParseOptions& options = {});
// Python-tuple lines "(t, bus_V, current_mA, power_mW)" from Arduino loggers. Options:
// tick_period_s (the first field is a timer tick, unwrapped at tick_bits, default 16),
// max_bus_v (default 16: rows above it are glitches and dropped).
PowerTrace parse_ina219_tuples(std::string_view text, const std::string& name, const ParseOptions& options = {});
// INA219 raw register logs: header time_s,shunt,bus[,current][,power]; see ina219.hpp for the
// decode and options.
PowerTrace parse_ina219_raw(std::string_view text, const std::string& name, const ParseOptions& options = {});
// nvidia-smi --query-gpu=timestamp,...,power.draw --format=csv[,nounits] [-lms N]. Options:
// column (default power.draw.instant when present, else power.draw), gpu (index or uuid value).
PowerTrace parse_nvidia_smi(std::string_view text, const std::string& name, const ParseOptions& options = {});
// tegrastats (TX1/TX2 "VDD_IN 3566/3566", Nano "POM_5V_IN 920/920", Xavier/Orin "VDD_IN
// 5542mW/5542mW"). Options: rail (default: the input rail VDD_IN / POM_5V_IN; "sum" adds all
// rails), interval_ms (used when lines carry no time stamp; default 1000).
PowerTrace parse_tegrastats(std::string_view text, const std::string& name, const ParseOptions& options = {});
// jetson-stats (jtop) CSV (csv.DictWriter over jtop's stats: time,uptime,...,Power <RAIL>,...,Power
// TOT,...; mW; zone-less local time). Options: rail (TOT by default; a rail name; sum = the rails
// outside the input rail, which holds them).
PowerTrace parse_jtop(std::string_view text, const std::string& name, const ParseOptions& options = {});
bool looks_like_jtop(std::string_view text);
// Raspberry Pi 5 PMIC dumps (`vcgencmd pmic_read_adc`, each after a time stamp line: `date +%s.%N`
// or an ISO stamp): power = sum of I x V over the rails with both readings. Options: interval_s
// (dumps without time stamps placed evenly).
PowerTrace parse_pi_pmic(std::string_view text, const std::string& name, const ParseOptions& options = {});
bool looks_like_pi_pmic(std::string_view text);
// PMT dumps: header "timestamp <sensor columns>", then "<t> <W>..." and `M <t> "label"` markers.
// Options: column (default: a column named *instant*, else the first).
PowerTrace parse_pmt(std::string_view text, const std::string& name, const ParseOptions& options = {});
// kentcz/rapl-tools AppPowerMeter CSV: headerless pkg_W,pp0_W,pp1_W,dram_W,elapsed_s.
// Options: domain (pkg|pp0|pp1|dram, default pkg).
PowerTrace parse_rapl_tools_csv(std::string_view text, const std::string& name, const ParseOptions& options = {});
// rapl-tools power.log summary: returns its "Total Energy" in joules (an oracle, not a trace).
double parse_rapl_tools_total_energy(std::string_view text, const std::string& name);
// `perf stat -a -e power/energy-pkg/ -x, -I ms`: joules per interval -> interval-mean watts.
PowerTrace parse_perf_stat(std::string_view text, const std::string& name, const ParseOptions& options = {});
// likwid-perfctr timeline mode (-t): rows "<group> <count> <threads> <runtime> <values...>",
// metric-major; likwid's '# GID|...' header names the metrics. Options: metric (NAME, or N without
// the header; default Power [W]), group (one group's rows when likwid switched groups).
PowerTrace parse_likwid_timeline(std::string_view text, const std::string& name, const ParseOptions& options = {});
bool looks_like_likwid_timeline(std::string_view text);
// Records of "Timestamp: <date>" + hwmon "curr1_input: mA" / "in1_input: mV" lines.
PowerTrace parse_hwmon_records(std::string_view text, const std::string& name, const ParseOptions& options = {});
// powerstat (vmstat-like table "Time User ... Watts", rows "HH:MM:SS ... W" until the "--------"
// summary). Options: column (default Watts; pkg-0, dram, ... with -D), date (YYYY-MM-DD: the
// time of day becomes absolute local time; without it times are seconds since midnight).
PowerTrace parse_powerstat(std::string_view text, const std::string& name, const ParseOptions& options = {});
// turbostat (--show Time_Of_Day_Seconds,PkgWatt,... ; --Summary or the per-CPU table, whose
// summary rows carry '-' as CPU). Options: column (default PkgWatt; CorWatt, RAMWatt, GFXWatt,
// SysWatt), interval_s (rows without Time_Of_Day_Seconds: from it, or from turbostat's "N.NNN sec"
// lines, else refused). A version banner and CPUID/MSR lines before the table are skipped.
PowerTrace parse_turbostat(std::string_view text, const std::string& name, const ParseOptions& options = {});
// PowerJoular CSV "Date,CPU Utilization,Total Power,CPU Power,GPU Power" (W, one row a second,
// each the mean over the second before its zone-less local stamp). Options: column (default Total
// Power when present, else CPU Power).
PowerTrace parse_powerjoular(std::string_view text, const std::string& name, const ParseOptions& options = {});
// trnkit's own log (written by the sysfs sampler and the INA219 simulator's decode):
// "# trnkit-power v1 kind=instant|interval-mean ..." then t_s,power_w lines.
PowerTrace parse_trnkit_power(std::string_view text, const std::string& name, const ParseOptions& options = {});

// Scaphandre JSON (`scaphandre json -f FILE`): JSON Lines or one array of measurement steps,
// microwatts. Options: part (host, socket:N or socket:N:DOMAIN; default host).
PowerTrace parse_scaphandre(std::string_view text, const std::string& name, const ParseOptions& options = {});
// Recognition helpers for `auto`: a JSON document (first non-blank character '{' or '['), and
// Scaphandre's among them.
bool looks_like_json(std::string_view text);
bool looks_like_scaphandre(std::string_view text);
// CodeCarbon emissions.csv: per-run summaries, not a trace; always refused here, naming
// `trnkit energy runs` (parse_codecarbon_runs in run_summaries.hpp reads the runs).
[[noreturn]] PowerTrace parse_codecarbon(std::string_view text, const std::string& name, const ParseOptions& options = {});

// Every format above by name; "auto" recognises a format from the text or refuses, saying why.
std::vector<std::string> power_log_formats();
std::string detect_power_log_format(std::string_view text, const std::string& name);
PowerTrace parse_power_log(std::string_view text, const std::string& name, const std::string& format = "auto",
                           const ParseOptions& options = {});
PowerTrace read_power_log(const std::string& path, const std::string& format = "auto", const ParseOptions& options = {});

// Writes a trace in trnkit's own format (parse_trnkit_power reads it back exactly).
std::string format_trnkit_power(const PowerTrace& trace);

}  // namespace trn::energy
TRN_API_END
