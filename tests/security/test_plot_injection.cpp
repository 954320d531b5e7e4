// Every plot entry point with labels that try to run a command through gnuplot: the canary is
// never created, the figure is still drawn and the label sits in the script as a gnuplot_string.
// Entry points: `trnkit localize` (flight.json `scenario`, a dataset folder whose name holds a
// newline), `trnkit energy integrate --platform ... --plot`, `trnkit energy compare` (the
// `platform` field of run reports) and the experiments' line_plot.
#include <algorithm>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../energy/synthetic_run.hpp"
#include "payloads.hpp"
#include "run_process.hpp"
#include "security_test_dir.hpp"
#include "table.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::test {
namespace {
namespace fs = std::filesystem;
using io::gnuplot_string;
using energy::test::make_timeline;
using energy::test::sample_trace;
using energy::test::TraceClock;

// Payloads a command line and a JSON file can carry (argv ends at NUL; JSON holds only UTF-8).
std::vector<std::string> text_payloads(const std::string& canary) {
    std::vector<std::string> out;
    for (const std::string& p : injection_payloads(canary)) {
        if (p.find('\0') != std::string::npos) continue;
        try {
            (void)nlohmann::json(p).dump();
            out.push_back(p);
        } catch (const nlohmann::json::exception&) {
        }
    }
    return out;
}

// The payloads a label may hold: since issue 46 a label with a control character (a line break
// would split a CSV row or a gnuplot line) is refused up front (energy/label_check.hpp), so those are
// tested as refusals, the rest as inert text.
bool has_control_character(const std::string& p) {
    return std::any_of(p.begin(), p.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}
std::vector<std::string> label_payloads(const std::string& canary) {
    std::vector<std::string> out = text_payloads(canary);
    std::erase_if(out, has_control_character);
    return out;
}

class PlotInjection : public SecurityTest {
protected:
    void SetUp() override {
        SecurityTest::SetUp();
        if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox): plots not drawn";
    }
    ProcessResult trnkit(std::vector<std::string> args) {
        // TRN_SECURITY_TRNKIT runs these checks against another build (e.g. an older one, to see them fail).
        const char* other = std::getenv("TRN_SECURITY_TRNKIT");
        args.insert(args.begin(), other && *other ? other : TRNKIT_EXE);
        return run_process(args, path("trnkit-output.txt"));
    }
    void expect_no_canary() { EXPECT_FALSE(fs::exists(canary_)) << "a label ran a command through gnuplot"; }
    static void expect_image(const std::string& png) {
        std::error_code ec;
        EXPECT_GT(fs::file_size(png, ec), 1000u) << png << " not drawn";
    }
    static void expect_in_script(const std::string& script, const std::string& label) {
        EXPECT_NE(slurp(script).find(gnuplot_string(label)), std::string::npos) << script << " lacks " << gnuplot_string(label);
    }
};

// A measurement run: 8 frames, markers on the real clock, a relative-time power log placed by --offset.
struct EnergyRun {
    std::string markers, log, offset;
};
EnergyRun write_energy_run(const std::string& dir) {
    const auto tl = make_timeline(8, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    const auto tr = sample_trace(tl.markers, TraceClock{-ref + 0.2, 0, ref}, 0, 0.2 + 3, 1e-3, 2.0, 3.0);
    EnergyRun r{dir + "/markers.csv", dir + "/power.log", ""};
    std::ofstream(r.markers) << energy::format_markers(tl.markers);
    std::ofstream(r.log) << energy::format_trnkit_power(tr);
    std::ostringstream os;
    os.precision(17);
    os << -ref + 0.2;
    r.offset = os.str();
    return r;
}

TEST_F(PlotInjection, EnergyIntegratePlatformOption) {
    const EnergyRun run = write_energy_run(dir_.string());
    const auto payloads = label_payloads(canary_);
    ASSERT_FALSE(payloads.empty());
    for (const std::string& p : text_payloads(canary_)) {
        if (!has_control_character(p)) continue;
        const ProcessResult refused = trnkit({"energy", "integrate", run.log, "--markers", run.markers, "--offset=" + run.offset, "--platform", p,
                                              "--json", path("refused.json")});
        EXPECT_EQ(refused.code, 1) << "a platform with a control character is refused up front\n" << refused.output;
        EXPECT_NE(refused.output.find("control character"), std::string::npos) << refused.output;
    }
    expect_no_canary();
    std::string all;  // every payload in one label (each one alone meets the real gnuplot in the unit test)
    for (const std::string& p : payloads) all += p + " | ";
    int k = 0;
    for (const std::string& platform : {payloads.front(), all}) {
        const std::string png = path("trace" + std::to_string(k++) + ".png");
        const ProcessResult r = trnkit({"energy", "integrate", run.log, "--markers", run.markers, "--offset=" + run.offset, "--platform",
                                        platform, "--json", path("run.json"), "--plot", png});
        ASSERT_EQ(r.code, 0) << r.output;
        expect_no_canary();
        expect_image(png);
        expect_in_script(png + ".gp", "Power trace with frames shaded: " + platform);
    }
}

TEST_F(PlotInjection, EnergyIntegratePlotPathIsNeverPastedIntoTheScript) {
    const EnergyRun run = write_energy_run(dir_.string());
    // A file name cannot hold '/', so the payload touches $TRN_CANARY (expanded by the shell that
    // gnuplot's `system` would start).
    const std::string png = path("it's\nsystem \"touch $TRN_CANARY\"\n#.png");
    ::setenv("TRN_CANARY", canary_.c_str(), 1);
    const ProcessResult r = trnkit({"energy", "integrate", run.log, "--markers", run.markers, "--offset=" + run.offset, "--platform", "A",
                                    "--json", path("run.json"), "--plot", png});
    ::unsetenv("TRN_CANARY");
    ASSERT_EQ(r.code, 0) << r.output;
    expect_no_canary();
    expect_image(png);
    const std::string name = io::plain_basename(fs::path(png).filename().string());
    EXPECT_EQ(slurp(path(name + ".gp")).find("system \"touch"), std::string::npos);
}

TEST_F(PlotInjection, EnergyComparePlatformFieldOfRunReports) {
    const auto payloads = label_payloads(canary_);
    std::vector<std::string> args = {"energy", "compare"};
    for (std::size_t k = 0; k < payloads.size(); ++k) {
        const auto tl = make_timeline(6, 0.05, 0.05);
        const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
        const auto tr = sample_trace(tl.markers, TraceClock{-ref + 0.2, 0, ref}, 0, 0.2 + 3, 1e-3, 2.0, 2.0 + k);
        energy::IntegrateRequest q;
        q.platform = payloads[k], q.align = energy::AlignMode::Offset, q.offset_s = -ref + 0.2;
        args.push_back(path("run" + std::to_string(k) + ".json"));
        std::ofstream(args.back()) << energy::run_report_json(energy::integrate_run(tr, tl.markers, q));
    }
    args.insert(args.end(), {"-o", path("compare")});
    const ProcessResult r = trnkit(args);
    ASSERT_EQ(r.code, 0) << r.output;
    expect_no_canary();
    for (const char* png : {"energy_histograms.png", "energy_boxplot.png", "frame_time_boxplot.png"}) expect_image(path("compare/") + png);
    for (const std::string& p : payloads) {
        expect_in_script(path("compare/energy_boxplot.png.gp"), p);
        expect_in_script(path("compare/energy_histograms.png.gp"), p + " (n = 6)");
    }
}

// One tiny AIR flight (5 filter steps), simulated once and copied into each localize test's folder.
class LocalizeInjection : public PlotInjection {
protected:
    static void SetUpTestSuite() {
        flight_ = fs::temp_directory_path() / ("trn_security_flight_" + std::to_string(::getpid()));
        fs::remove_all(flight_);
        fs::create_directories(flight_);
        simulated_ = run_process({TRNKIT_EXE, "simulate", "--scenario", "FR-200", "--frames", "24", "--size-m", "600", "--out",
                                  (flight_ / "flight").string()},
                                 (flight_ / "simulate.txt").string());
    }
    static void TearDownTestSuite() { fs::remove_all(flight_); }
    void SetUp() override {
        PlotInjection::SetUp();
        if (IsSkipped()) return;
        ASSERT_EQ(simulated_.code, 0) << simulated_.output;
        fs::copy(flight_ / "flight", path("flight"), fs::copy_options::recursive);
    }
    ProcessResult localize(const std::string& dataset, const std::vector<std::string>& more) {
        std::vector<std::string> args = {"localize", "--dataset", dataset, "--backend", "cpu", "--rate", "10", "--max-particles", "150",
                                         "--min-particles", "50", "--seed", "3"};
        args.insert(args.end(), more.begin(), more.end());
        return trnkit(args);
    }
    static inline fs::path flight_;
    static inline ProcessResult simulated_;
};

TEST_F(LocalizeInjection, ScenarioFieldOfFlightJson) {
    const std::string info = path("flight/flight.json");
    nlohmann::json j = nlohmann::json::parse(slurp(info));
    // Every payload at once (each one alone is checked against the real gnuplot in the unit test).
    std::string scenario;
    for (const std::string& p : text_payloads(canary_)) scenario += p + " | ";
    j["scenario"] = scenario;
    std::ofstream(info) << j.dump();
    const ProcessResult r = localize(path("flight"), {"--out", path("out")});
    ASSERT_EQ(r.code, 0) << r.output;
    expect_no_canary();
    expect_image(path("out/trajectory.png"));
    expect_image(path("out/error.png"));
    expect_in_script(path("out/plot.gp"), scenario + ": trajectories on the map");
    expect_in_script(path("out/plot.gp"), scenario + ": position error over distance flown");
}

TEST_F(LocalizeInjection, DatasetFolderNameWithANewline) {
    // A folder name cannot hold '/', so the payload touches $TRN_CANARY (expanded by the shell
    // that gnuplot's `system` would start); the default output folder is DATASET/localize.
    ::setenv("TRN_CANARY", canary_.c_str(), 1);
    const std::string dataset = path("run`touch $TRN_CANARY`\nsystem 'touch $TRN_CANARY'\n!touch $TRN_CANARY\n#");
    fs::rename(path("flight"), dataset);
    const ProcessResult r = localize(dataset, {});
    ::unsetenv("TRN_CANARY");
    ASSERT_EQ(r.code, 0) << r.output;
    expect_no_canary();
    expect_image(dataset + "/localize/trajectory.png");
    expect_image(dataset + "/localize/error.png");
    EXPECT_EQ(slurp(dataset + "/localize/plot.gp").find("touch"), std::string::npos);
}

TEST_F(PlotInjection, ExperimentsLinePlotTexts) {
    const std::vector<std::vector<double>> data = {{1, 2, 3}, {0.5, 0.25, 0.125}, {1, 0.5, 0.25}};
    // Every payload in every text: title, axis labels and column titles take turns.
    const auto payloads = injection_payloads(canary_);
    for (std::size_t k = 0; k < payloads.size(); k += 5) {
        const auto p = [&](std::size_t i) { return payloads[(k + i) % payloads.size()]; };
        const std::string png = path("fig" + std::to_string(k) + ".png");
        experiments::line_plot(png, p(0), p(1), p(2), data, {p(3), p(4)}, {.x_tic_step = 1, .vertical_lines = {1.5}});
        expect_no_canary();
        expect_image(png);
        for (std::size_t i = 0; i < 5; ++i) expect_in_script(png + ".gp", p(i));
    }
    // The output folder (a user's --out) is never named in the script either; a folder name cannot
    // hold '/', so it touches $TRN_CANARY (expanded by the shell gnuplot's `system` would start).
    ::setenv("TRN_CANARY", canary_.c_str(), 1);
    const std::string folder = path("out\nsystem \"touch $TRN_CANARY\"\n#");
    fs::create_directories(folder);
    experiments::line_plot(folder + "/fig.png", "t", "x", "y", data, {"a", "b"});
    ::unsetenv("TRN_CANARY");
    expect_no_canary();
    expect_image(folder + "/fig.png");
    EXPECT_EQ(slurp(folder + "/fig.png.gp").find("touch"), std::string::npos);
}

}  // namespace
}  // namespace trn::test
