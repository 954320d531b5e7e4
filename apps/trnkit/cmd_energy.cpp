// `trnkit energy ...`: the energy harness. Built so far: `inspect` (parse a power log and report
// its sampling hygiene) and `integrate-span` (energy of one time span of a log); integrate,
// compare and sample live in cmd_energy_*.cpp.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "options.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_summaries.hpp"
#include "trn/error.hpp"

namespace trn::cli {

// Further `energy` subcommands, each in its own cmd_energy_*.cpp.
void add_energy_integrate_command(CLI::App* energy);
void add_energy_compare_command(CLI::App* energy);
void add_energy_sample_command(CLI::App* energy);
void add_energy_formats_command(CLI::App* energy);
void add_log_time_zone_options(CLI::App* c, std::vector<std::string>* opts);
void add_energy_bench_command(CLI::App* energy);  // cmd_energy_bench.cpp

void add_energy_command(CLI::App& app) {
    auto* energy = app.add_subcommand("energy", "Power logs -> joules (inspect, runs, integrate-span, integrate, compare, sample, bench, formats)");
    energy->require_subcommand(1);
    struct Args {
        std::string log, format = "auto";
        std::vector<std::string> opts;
        double start = 0, end = 0;
        bool hold = false;
    };
    auto a = std::make_shared<Args>();
    auto add_log_options = [a](CLI::App* c) {
        c->add_option("log", a->log, "Power log file")->required();
        c->add_option("--format", a->format, "auto or a format name (see docs/ENERGY.md)")->capture_default_str();
        c->add_option("--opt", a->opts, "Parser option KEY=VALUE (repeatable)");
        add_log_time_zone_options(c, &a->opts);
    };
    auto* inspect = energy->add_subcommand("inspect", "Parse a power log and report format, sample rate, gaps and hygiene notes");
    add_log_options(inspect);
    inspect->callback([a] {
        const auto tr = energy::read_power_log(a->log, a->format, energy::parse_option_list(a->opts));
        const auto s = energy::describe_sampling(tr);
        std::printf("%s: format %s, power = %s\n", tr.source.c_str(), tr.format.c_str(), tr.quantity.c_str());
        std::printf("  %zu samples over %.6g s, median interval %.6g s (%.4g Hz), %zu gap(s) > 3x median (longest %.6g s), %zu stale repeat(s)\n",
                    s.samples, s.duration_s, s.median_dt_s, s.rate_hz, s.gaps, s.longest_gap_s, s.stale_repeats);
        const auto e = energy::integrate_interval(tr, tr.first_interval_start.value_or(tr.t.front()), tr.t.back());
        std::printf("  whole log: %.6g J (+- %.3g J)\n", e.energy_j, e.error_j);
        for (const auto& n : tr.notes) std::printf("  note: %s\n", n.c_str());
        for (const auto& w : tr.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        for (const auto& m : tr.markers) std::printf("  marker: %.6f %s\n", m.t, m.label.c_str());
    });
    auto* runs = energy->add_subcommand("runs", "List the runs of a per-run energy summary (CodeCarbon emissions.csv) and their joules, per machine");
    runs->add_option("log", a->log, "Summary file")->required();
    runs->add_option("--opt", a->opts, "Reader option KEY=VALUE (repeatable)");
    runs->callback([a] { std::fputs(energy::format_run_summaries(energy::read_run_summaries(a->log, energy::parse_option_list(a->opts))).c_str(), stdout); });
    auto* span = energy->add_subcommand("integrate-span", "Energy of [--start, --end] (seconds on the log's clock)");
    add_log_options(span);
    span->add_option("--start", a->start, "Start time (s)")->required()->check(real_in(-1e12, 1e12));
    span->add_option("--end", a->end, "End time (s)")->required()->check(real_in(-1e12, 1e12));
    span->add_flag("--hold", a->hold, "Zero-order hold instead of the trapezoid rule");
    span->callback([a] {
        if (!(a->end > a->start)) throw Error("--end " + std::to_string(a->end) + " must be after --start " + std::to_string(a->start));
        const auto tr = energy::read_power_log(a->log, a->format, energy::parse_option_list(a->opts));
        for (const auto& w : tr.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        const auto e = energy::integrate_interval(tr, a->start, a->end, a->hold ? energy::Rule::Hold : energy::Rule::Trapezoid);
        if (!e.covered) throw trn::Error(a->log + ": the span [" + std::to_string(a->start) + ", " + std::to_string(a->end) + "] s is not covered by the log");
        std::printf("%.9g J +- %.3g J (%zu samples inside)\n", e.energy_j, e.error_j, e.samples);
    });
    add_energy_integrate_command(energy);
    add_energy_compare_command(energy);
    add_energy_sample_command(energy);
    add_energy_formats_command(energy);
    add_energy_bench_command(energy);
}

}  // namespace trn::cli
