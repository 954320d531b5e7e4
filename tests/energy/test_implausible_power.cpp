// Readings no logger can mean (a -1e6 W glitch, 100 kW on a Jetson rail) are dropped, counted
// and surfaced as run-report warnings naming file:line, never integrated; a tegrastats line
// whose summed rails differ from the first line's is refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../cli/cli_process.hpp"
#include "synthetic_run.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"
#include "../common/shared_data.hpp"

namespace trn::energy {
namespace {

// The text of `log` with the power of data row `row` (0-based, after the header) replaced.
std::string with_power(const std::string& log, std::size_t row, const std::string& power, std::size_t* line_number) {
    std::istringstream in(log);
    std::ostringstream out;
    std::string line;
    std::size_t n = 0, data = 0;
    bool in_data = false;
    while (std::getline(in, line)) {
        ++n;
        if (in_data && data++ == row) {
            line = line.substr(0, line.find(',') + 1) + power;
            *line_number = n;
        }
        if (line == "t_s,power_w") in_data = true;
        out << line << "\n";
    }
    return out.str();
}

bool mentions(const std::vector<std::string>& list, const std::string& part) {
    for (const auto& s : list)
        if (s.find(part) != std::string::npos) return true;
    return false;
}

TEST(ImplausiblePower, GlitchIsDroppedWarnedAndKeptOutOfTheIdleBaseline) {
    const auto tl = test::make_timeline(10, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    const PowerTrace clean = test::sample_trace(tl.markers, test::TraceClock{0, 0, ref}, ref - 0.1, ref + 2.5, 1e-3, 2.0, 3.0, 0, true);
    std::size_t line = 0;
    // Row 150 lies in the lead idle (0.1 s before the run + 0.05 s into it).
    const std::string text = with_power(format_trnkit_power(clean), 150, "-1e6", &line);
    const PowerTrace tr = parse_power_log(text, "glitch.log");
    EXPECT_EQ(tr.size(), clean.size() - 1);
    ASSERT_EQ(tr.warnings.size(), 1u);
    EXPECT_NE(tr.warnings[0].find("glitch.log: dropped 1 implausible"), std::string::npos) << tr.warnings[0];
    EXPECT_NE(tr.warnings[0].find("line " + std::to_string(line) + ": -1e+06 W"), std::string::npos) << tr.warnings[0];
    const RunReport r = integrate_run(tr, tl.markers, IntegrateRequest{});
    EXPECT_NEAR(r.idle_w, 2.0, 0.05);  // one -1e6 W sample integrated would pull it hundreds of watts negative
    EXPECT_TRUE(mentions(r.warnings, "implausible")) << "the run report must carry the warning";
    EXPECT_NE(run_report_json(r).find("implausible"), std::string::npos);
}

// The CLI says so on stderr for every command that reads the log, and the report keeps it.
TEST(ImplausiblePower, CliWarnsOnStderr) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("trn_implausible_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto tl = test::make_timeline(10, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    std::size_t line = 0;
    const std::string log = (dir / "p.log").string(), markers = (dir / "m.csv").string(), json = (dir / "r.json").string();
    std::ofstream(log) << with_power(format_trnkit_power(test::sample_trace(tl.markers, test::TraceClock{0, 0, ref}, ref - 0.1, ref + 2.5, 1e-3, 2.0, 3.0, 0, true)),
                                     150, "-1e6", &line);
    std::ofstream(markers) << format_markers(tl.markers);
    const std::string expect = "warning: " + log + ": dropped 1 implausible power reading(s)";
    for (const std::string& args : {"energy integrate " + log + " --markers " + markers + " --json " + json, "energy inspect " + log,
                                    "energy integrate-span " + log + " --start " + std::to_string(ref) + " --end " + std::to_string(ref + 1)}) {
        const auto r = trn::test::run_trnkit(args);
        EXPECT_EQ(r.code, 0) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(expect), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_TRUE(mentions(read_run_report(json).warnings, "line " + std::to_string(line) + ": -1e+06 W"));
    fs::remove_all(dir);
}

TEST(ImplausiblePower, CeilingPerSourceAndNegativeReadings) {
    const std::string head = "# trnkit-power v1 kind=instant format=trnkit quantity=power wall_clock=0 resolution_w=0\nt_s,power_w\n";
    // trnkit's own log is capped as a node (20 kW, issue 26): 30 kW is a glitch; a small negative
    // reading (sensor offset near 0 W) is kept and warned.
    const PowerTrace tr = parse_power_log(head + "0,1.5\n1,-0.2\n2,30000\n3,1.5\n", "spike.log");
    EXPECT_EQ(tr.size(), 3u);
    ASSERT_EQ(tr.warnings.size(), 2u);
    EXPECT_NE(tr.warnings[0].find("line 5: 30000 W"), std::string::npos) << tr.warnings[0];
    EXPECT_NE(tr.warnings[1].find("1 negative power reading(s) kept as read (first at line 4"), std::string::npos) << tr.warnings[1];
    // A source that cannot draw negative power refuses it, naming the line.
    try {
        parse_power_log(head + "0,-5\n1,-5\n2,-5\n", "reversed.log", "auto", {{"source", "gpu"}});
        FAIL() << "a GPU log of negative power was accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("reversed.log:3: negative power -5 W"), std::string::npos) << e.what();
    }
    // A log with nothing plausible left is refused, saying why.
    try {
        parse_power_log(head + "0,1e6\n1,1e6\n2,1e6\n", "huge.log");
        FAIL() << "a log of implausible power was accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("implausible"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
    }
}

std::string powerlogs() {
    const std::string p = trn::test::shared_data("powerlogs");
    return !p.empty() && std::filesystem::is_directory(p) ? p : "";
}

std::vector<std::string> read_lines(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

std::string join(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

TEST(ImplausiblePower, RealTegrastatsRailGlitchIsWarned) {
    const std::string dir = powerlogs();
    if (dir.empty()) GTEST_SKIP() << "TRN_SHARED_DATA/powerlogs not found: real power logs unavailable";
    auto lines = read_lines(dir + "/tegrastats/sumantbagri_jetson-nano_tegrastats.txt");
    ASSERT_GT(lines.size(), 5u);
    const auto at = lines[3].find("POM_5V_IN ");
    ASSERT_NE(at, std::string::npos);
    lines[3].replace(at, lines[3].find(' ', at + 10) - at, "POM_5V_IN 99999999/920");  // 100 kW on a 10 W board
    const PowerTrace tr = parse_power_log(join(lines), "nano.txt");
    EXPECT_EQ(tr.size(), lines.size() - 1);
    ASSERT_EQ(tr.warnings.size(), 1u);
    EXPECT_NE(tr.warnings[0].find("line 4: 100000 W"), std::string::npos) << tr.warnings[0];
}

TEST(ImplausiblePower, RealOrinSumMissingARailIsRefused) {
    const std::string dir = powerlogs();
    if (dir.empty()) GTEST_SKIP() << "TRN_SHARED_DATA/powerlogs not found: real power logs unavailable";
    auto lines = read_lines(dir + "/tegrastats/hanner123_agx-orin-64gb_tegrastats.log");
    ASSERT_GT(lines.size(), 5u);
    // The Orin has no input rail, so its total is the sum of all rails: drop one from line 3.
    const auto at = lines[2].find(" VDD_CPU_CV ");
    ASSERT_NE(at, std::string::npos);
    lines[2].erase(at, lines[2].find(' ', lines[2].find('/', at)) - at);
    for (const ParseOptions& o : {ParseOptions{}, ParseOptions{{"rail", "sum"}}}) {
        try {
            parse_power_log(join(lines), "orin.log", "tegrastats", o);
            FAIL() << "a summed line missing a rail was accepted";
        } catch (const trn::Error& e) {
            const std::string why = e.what();
            EXPECT_NE(why.find("orin.log:3:"), std::string::npos) << why;
            EXPECT_NE(why.find("line 1"), std::string::npos) << why;
        }
    }
}

}  // namespace
}  // namespace trn::energy
