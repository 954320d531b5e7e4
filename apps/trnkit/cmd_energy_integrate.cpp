// `trnkit energy integrate LOG --markers M.csv`: per-frame joules (gross, net above idle, sample
// count, error bound, flags) as JSON and CSV, with the markers put on the log's clock by the
// same clock, an explicit offset, or automatic alignment.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "field_flags.hpp"
#include "options.hpp"
#include "write_text.hpp"
#include "trn/energy/plots.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/input_file.hpp"
#include <utility>

namespace trn::cli {

void add_log_time_zone_options(CLI::App* c, std::vector<std::string>* opts);  // cmd_energy_formats.cpp

void add_energy_integrate_command(CLI::App* energy) {
    struct Args {
        std::string log, format = "auto", markers, align, platform, json, csv, plot, clock = "real";
        std::vector<std::string> opts;
        double offset = 0, search = 0;
        bool hold = false, insist = false;
        std::size_t min_samples = 3;
    };
    auto a = std::make_shared<Args>();
    auto* c = energy->add_subcommand("integrate", "Per-frame energy of a power log between frame markers (trnkit frames, minimal frame,start_s,end_s, or the log's own)");
    c->add_option("log", a->log, "Power log file")->required();
    c->add_option("--format", a->format, "auto or a format name (see trnkit energy formats)")->capture_default_str();
    c->add_option("--opt", a->opts, "Parser option KEY=VALUE (repeatable)");
    add_log_time_zone_options(c, &a->opts);
    c->add_option("--markers", a->markers,
                  "Marker file: trnkit frames / energy bench / MeasurementWindows, or minimal 'frame,start_s,end_s' on the log's clock; "
                  "omit to use the log's own start/end markers (PMT)");
    auto* offset = c->add_option("--offset", a->offset, "Log time = marker time + OFFSET (s); with --align auto: centre of the search")
                       ->check(real_in(-1e12, 1e12));
    c->add_option("--align", a->align, "auto: estimate offset and drift from the busy/idle pattern")->check(CLI::IsMember({"auto"}));
    c->add_option("--search", a->search, "With --align auto: search OFFSET +- this many seconds (default: everywhere)")->check(real_in(0, 1e12));
    c->add_flag("--insist", a->insist, "With --align auto: accept an ambiguous estimate (kept as a warning in the report) instead of refusing");
    c->add_option("--clock", a->clock, "Marker clock: real (CLOCK_REALTIME) or mono (CLOCK_MONOTONIC)")->capture_default_str()->check(CLI::IsMember({"real", "mono"}));
    c->add_flag("--hold", a->hold, "Zero-order hold instead of the trapezoid rule");
    c->add_option("--min-samples", a->min_samples, "Frames with fewer samples are flagged")->capture_default_str()->transform(whole_in(0, 1000000));
    c->add_option("--platform", a->platform, "Platform label for compare (default from the markers: backend/kernel/size)");
    c->add_option("--json", a->json, "Write the run report JSON here (default: standard output)");
    c->add_option("--csv", a->csv, "Write per-frame CSV here");
    c->add_option("--plot", a->plot, "Draw the power trace with frames shaded (PNG, gnuplot)");
    c->callback([a, offset] {
        energy::IntegrateRequest q;
        q.platform = a->platform;
        q.realtime = a->clock == "real";
        q.offset_s = a->offset, q.search_s = a->search, q.insist = a->insist;
        q.align = !a->align.empty() ? energy::AlignMode::Auto : offset->count() ? energy::AlignMode::Offset : energy::AlignMode::SameClock;
        q.integration.rule = a->hold ? energy::Rule::Hold : energy::Rule::Trapezoid;
        q.integration.min_samples = a->min_samples;
        const auto opts = energy::parse_option_list(a->opts);
        for (const auto& [option, out] : {std::pair{"--json", a->json}, {"--csv", a->csv}, {"--plot", a->plot}})
            io::check_output_is_not_input(out, option, {{"log", a->log}, {"--markers", a->markers}});
        if (!a->json.empty()) io::check_output_file(a->json, "--json");
        if (!a->csv.empty()) io::check_output_file(a->csv, "--csv");
        if (!a->plot.empty()) io::check_output_file(a->plot, "--plot");
        const energy::RunReport r = energy::integrate_files(a->log, a->format, opts, a->markers, q);
        const std::string json = energy::run_report_json(r);
        if (a->json.empty()) std::cout << json;  // checked at exit (main.cpp)
        else write_text_file(a->json, json);
        if (!a->csv.empty()) write_text_file(a->csv, energy::run_report_csv(r));
        // Summary on stderr so stdout stays pure JSON.
        double sum = 0;
        std::size_t usable = 0;
        for (const auto& f : r.frames)
            if (f.energy.flag.empty()) sum += f.energy.net_j, ++usable;
        std::fprintf(stderr, "%s: %zu frame(s), %zu usable, mean net %.6g mJ/frame, idle %.4g W; align %s offset %.6f s drift %.3g (residual %.3g s); "
                     "markers +-1 sample (%.3g s) move energies by %.3g%% / %.3g%%\n",
                     io::quote_input(r.platform, 200).c_str(), r.frames.size(), usable, usable ? 1e3 * sum / usable : 0.0, r.idle_w, r.align_mode.c_str(),
                     r.alignment.mapping.offset_s, r.alignment.mapping.drift, r.alignment.residual_s, r.shift.dt_s, 100 * r.shift.relative_minus,
                     100 * r.shift.relative_plus);
        if (r.align_mode == "auto") std::fprintf(stderr, "  alignment confidence: %s\n", r.alignment.confidence.c_str());
        // Warnings quote input text: control characters escaped, so a log or marker file cannot drive the terminal.
        for (const auto& w : r.warnings) std::fprintf(stderr, "  warning: %s\n", io::quote_input(flags_in(w), 1000).c_str());
        if (!a->plot.empty()) {
            const auto trace = energy::read_power_log(a->log, a->format, opts);
            energy::plot_power_trace(trace, r, a->plot);
        }
    });
}

}  // namespace trn::cli
