// `trnkit energy compare A.json B.json ...`: the dissertation's three tables (Markdown + CSV),
// a summary JSON with provenance, and gnuplot figures (histograms with the mean, box plots).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "options.hpp"
#include "write_text.hpp"
#include "trn/energy/compare.hpp"
#include "trn/energy/plots.hpp"
#include "trn/error.hpp"
#include "trn/io/output_folder.hpp"

namespace trn::cli {

void add_energy_compare_command(CLI::App* energy) {
    struct Args {
        std::vector<std::string> runs;
        std::string out = "energy-compare", energy = "net", test, unit = "auto", plot_format = "png";
        bool student = false, no_plots = false, force = false;
        std::size_t bootstrap = 10000;
    };
    auto a = std::make_shared<Args>();
    auto* c = energy->add_subcommand("compare", "Compare platforms from run reports of `energy integrate`: tables, summary JSON, plots");
    c->add_option("runs", a->runs, "Run report JSON files (runs with the same platform label are pooled)")->required();
    c->add_option("-o,--out", a->out, "Output folder (created if missing)")->capture_default_str();
    c->add_option("--energy", a->energy, "net (above idle) or gross energy")->capture_default_str()->check(CLI::IsMember({"net", "gross"}));
    c->add_flag("--student", a->student, "Student's t-test (equal variances) instead of Welch's (same as --test student)");
    c->add_option("--test", a->test, "t-test: welch (default), student, or both (each Holm-corrected on its own)")->check(CLI::IsMember({"welch", "student", "both"}));
    c->add_option("--unit", a->unit, "Unit of the tests: auto (runs when every platform has >= 2 runs), runs (per-run mean energies) or frames")
        ->capture_default_str()->check(CLI::IsMember({"auto", "runs", "frames"}));
    c->add_option("--bootstrap", a->bootstrap, "Resamples for the bootstrap CI of the energy ratio")->capture_default_str()->transform(whole_in(100, 1000000));
    c->add_option("--plot-format", a->plot_format, "Figure format: png, pdf or svg")->capture_default_str()->check(CLI::IsMember({"png", "pdf", "svg"}));
    c->add_flag("--no-plots", a->no_plots, "Skip the gnuplot figures");
    c->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of energy compare");
    c->callback([a] {
        energy::CompareOptions o;
        if (a->student && !a->test.empty() && a->test != "student") throw Error("--student and --test " + a->test + ": give one of them");
        o.student = a->student || a->test == "student", o.both = a->test == "both", o.net = a->energy == "net";
        o.unit = a->unit == "runs" ? energy::TestUnit::Runs : a->unit == "frames" ? energy::TestUnit::Frames : energy::TestUnit::Auto;
        o.bootstrap_resamples = a->bootstrap;
        io::check_output_folder(a->out, "energy compare", a->force);
        const auto cmp = energy::compare_files(a->runs, o);
        io::open_output_folder(a->out, "energy compare", a->force, "--out", io::Rerun::ReplacesPrevious);
        write_text_file(a->out + "/tables.md", energy::tables_markdown(cmp));
        write_text_file(a->out + "/table1_energy.csv", energy::energy_table_csv(cmp));
        write_text_file(a->out + "/table2_shapiro_wilk.csv", energy::shapiro_table_csv(cmp));
        write_text_file(a->out + "/table3_t_tests.csv", energy::ttest_table_csv(cmp));
        write_text_file(a->out + "/table4_rank_tests_ratios.csv", energy::rank_ratio_table_csv(cmp));
        write_text_file(a->out + "/summary.json", energy::comparison_json(cmp));
        // The summary on stdout, the tables in files.
        std::cout << energy::comparison_summary_text(cmp) << "tables: " << a->out
                  << "/{tables.md,table1_energy.csv,table2_shapiro_wilk.csv,table3_t_tests.csv,table4_rank_tests_ratios.csv,summary.json}\n";
        if (a->no_plots) return;
        std::vector<energy::PlotSeries> e, t;
        for (const auto& p : cmp.platforms) e.push_back({p.name, p.energy_mj}), t.push_back({p.name, p.frame_ms});
        const std::string unit = std::string(o.net ? "net" : "gross") + " energy per frame (mJ)";
        const std::string ext = "." + a->plot_format;
        energy::plot_histograms(e, a->out + "/energy_histograms" + ext, unit);
        energy::plot_boxes(e, a->out + "/energy_boxplot" + ext, unit);
        energy::plot_boxes(t, a->out + "/frame_time_boxplot" + ext, "frame time (ms)");
        std::cout << "plots: " << a->out << "/{energy_histograms,energy_boxplot,frame_time_boxplot}" << ext << "\n";
    });
}

}  // namespace trn::cli
