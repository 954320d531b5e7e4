// `trnkit energy compare` as a user runs it (real processes): the summary on stdout and the
// tables in files, Welch and Student together, and figures as PNG, PDF or SVG (issue 16).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../cli/cli_process.hpp"
#include "synthetic_run.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/plots.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Reports {
    fs::path dir = fs::temp_directory_path() / ("trn_compare_cli_" + std::to_string(::getpid()));
    std::string a, b;
    Reports() {
        fs::remove_all(dir);
        fs::create_directories(dir);
        std::vector<double> ea, eb;
        for (int i = 0; i < 60; ++i) ea.push_back(0.010 * (1 + 0.1 * std::sin(i * 2.1))), eb.push_back(0.013 * (1 + 0.1 * std::cos(i * 1.3)));
        a = (dir / "a.json").string(), b = (dir / "b.json").string();
        std::ofstream(a) << run_report_json(test::report_with_energies("cpu-A", ea, "la"));
        std::ofstream(b) << run_report_json(test::report_with_energies("cpu-B", eb, "lb"));
    }
    ~Reports() { fs::remove_all(dir); }
};

TEST(CompareCli, SummaryOnStdoutTablesInFilesBothTests) {
    Reports r;
    const fs::path out = r.dir / "out";
    const auto res = trn::test::run_trnkit("energy compare " + r.a + " " + r.b + " --test both --bootstrap 500 --no-plots -o " + out.string());
    ASSERT_EQ(res.code, 0) << res.output;
    EXPECT_EQ(res.output.find("## Table"), std::string::npos) << "tables belong in files:\n" << res.output;
    for (const char* s : {"cpu-A vs cpu-B: ratio 0.7", "Welch p(Holm) = ", "Student p(Holm) = ", "Mann-Whitney p(Holm) = ", "bootstrap 95 % CI"})
        EXPECT_NE(res.output.find(s), std::string::npos) << s << "\n" << res.output;
    const std::string md = slurp(out / "tables.md");
    for (const char* s : {"## Table 1", "## Table 4", "| Welch |", "| Student |"}) EXPECT_NE(md.find(s), std::string::npos) << s;
    const std::string t3 = slurp(out / "table3_t_tests.csv");
    EXPECT_EQ(std::count(t3.begin(), t3.end(), '\n'), 3) << t3;  // header, Welch, Student
    EXPECT_TRUE(fs::exists(out / "table4_rank_tests_ratios.csv"));
    const auto clash = trn::test::run_trnkit("energy compare " + r.a + " " + r.b + " --student --test welch --no-plots --force -o " + out.string());
    EXPECT_EQ(clash.code, 1) << clash.output;
    EXPECT_NE(clash.output.find("--student and --test welch"), std::string::npos) << clash.output;
}

TEST(CompareCli, FiguresAsPdfAndSvgWithSharedRangeAndMeans) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox): figures not drawn";
    Reports r;
    for (const char* format : {"svg", "pdf"}) {
        const fs::path out = r.dir / format;
        const auto res = trn::test::run_trnkit("energy compare " + r.a + " " + r.b + " --bootstrap 200 --plot-format " + format + " -o " + out.string());
        ASSERT_EQ(res.code, 0) << res.output;
        for (const char* f : {"energy_histograms", "energy_boxplot", "frame_time_boxplot"}) {
            const fs::path img = out / (std::string(f) + "." + format);
            ASSERT_TRUE(fs::exists(img)) << img;
            const std::string head = slurp(img).substr(0, 400);
            EXPECT_NE(head.find(std::string(format) == "pdf" ? "%PDF" : "<svg"), std::string::npos) << img;
        }
        // One x range for every histogram panel, y from 0, the key outside the bars; box plots mark the mean.
        const std::string hist = slurp(out / (std::string("energy_histograms.") + format + ".gp"));
        EXPECT_NE(hist.find("set xrange ["), std::string::npos);
        EXPECT_NE(hist.find("set yrange [0:*]"), std::string::npos);
        EXPECT_NE(hist.find("set key outside"), std::string::npos);
        const std::string box = slurp(out / (std::string("energy_boxplot.") + format + ".gp"));
        EXPECT_NE(box.find("title 'mean'"), std::string::npos);
    }
}

TEST(CompareCli, TracePlotHasAZoomPanelWithFrameMarkers) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox): figures not drawn";
    Reports r;
    const auto tl = test::make_timeline(6, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    const auto tr = test::sample_trace(tl.markers, test::TraceClock{-ref + 1, 0, ref}, 0, 3.5, 2e-3, 2.0, 3.0);
    const std::string log = (r.dir / "p.log").string(), markers = (r.dir / "m.csv").string(), img = (r.dir / "trace.svg").string();
    std::ofstream(log) << format_trnkit_power(tr);
    std::ofstream(markers) << format_markers(tl.markers);
    char offset[64];
    std::snprintf(offset, sizeof offset, "--offset=%.9f", -ref + 1);
    const auto res = trn::test::run_trnkit("energy integrate " + log + " --markers " + markers + " " + offset + " --json " + (r.dir / "run.json").string() +
                                           " --plot " + img);
    ASSERT_EQ(res.code, 0) << res.output;
    EXPECT_NE(slurp(img).find("<svg"), std::string::npos);
    const std::string gp = slurp(r.dir / "trace.svg.gp");
    for (const char* s : {"set multiplot layout 2,1", "Zoom: first 3 frame(s)", "set arrow 6 from", "frame 2", "title 'frame start'"})
        EXPECT_NE(gp.find(s), std::string::npos) << s << "\n" << gp;
}

TEST(Plots, SharedBinsHoldEveryValueOfEverySeries) {
    const std::vector<PlotSeries> s = {{"a", {1.0, 1.5, 2.0}}, {"b", {3.0, 4.0, 5.0, 6.0}}};
    const HistogramBins b = shared_bins(s);
    EXPECT_DOUBLE_EQ(b.lo, 1.0);
    for (const auto& x : s)
        for (double v : x.values) {
            const double k = std::floor((v - b.lo) / b.width);
            EXPECT_GE(k, 0) << v;
            EXPECT_LT(k, b.bins) << v << ": outside the drawn bins";
        }
    // A tight platform beside a wide one still gets several bars (the narrowest spread sets the width).
    std::vector<double> narrow;
    for (int i = 0; i < 16; ++i) narrow.push_back(3.0 + 0.025 * i);
    const HistogramBins nb = shared_bins({{"wide", {1.0, 2.0, 4.0, 6.0}}, {"narrow", narrow}});
    EXPECT_GE((3.375 - 3.0) / nb.width, 4.0) << nb.width;
    EXPECT_LE(nb.bins, 121);
    EXPECT_NE(terminal_for("x.pdf", 900, 300).find("pdfcairo"), std::string::npos);
    EXPECT_NE(terminal_for("x.SVG", 900, 300).find("terminal svg"), std::string::npos);
    EXPECT_NE(terminal_for("x.png", 900, 300).find("pngcairo"), std::string::npos);
    for (const char* t : {"x.pdf", "x.svg", "x.png"}) EXPECT_NE(terminal_for(t, 900, 300).find("noenhanced"), std::string::npos) << t;
}

}  // namespace
}  // namespace trn::energy
