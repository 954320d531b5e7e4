// End to end as a user runs it: `trnkit frames` (cpu backend, a few frames) -> a synthetic power
// log built to match its markers on an unknown clock offset -> `trnkit energy integrate --align
// auto` -> `trnkit energy compare` of two such runs: tables, summary JSON and (with gnuplot) plots.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "synthetic_run.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

int run(const std::string& args) { return std::system((std::string(TRNKIT_EXE) + " " + args + " >/dev/null 2>&1").c_str()); }

std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

struct MeasuredRun {
    fs::path markers, log, json;
};

// Markers from the real frame runner; the log puts the run 1.25 s into a relative-time trace.
MeasuredRun measured_run(const fs::path& dir, const std::string& name, double busy_w) {
    MeasuredRun r{dir / (name + "_markers.csv"), dir / (name + "_power.log"), dir / (name + ".json")};
    EXPECT_EQ(run("frames -b cpu -k 12 --size 480p --idle-ms 15 --lead-idle-ms 150 --sync-unit-ms 20 -o " + r.markers.string()), 0);
    const MarkerFile m = read_markers(r.markers.string());
    double shortest = 1;
    for (const auto& row : m.rows) shortest = std::min(shortest, (row.real_end_ns - row.real_start_ns) * 1e-9);
    const double dt = std::clamp(shortest / 6, 10e-6, 1e-3);
    const double ref = m.rows.front().real_start_ns * 1e-9, span = m.rows.back().real_end_ns * 1e-9 - ref;
    PowerTrace tr = test::sample_trace(m, test::TraceClock{-ref + 1.25, 0, ref}, 0, 1.25 + span + 0.5, dt, 1.5, busy_w);
    std::ofstream(r.log) << format_trnkit_power(tr);
    return r;
}

TEST(EndToEnd, FramesIntegrateCompare) {
    const fs::path dir = fs::temp_directory_path() / ("trn_energy_e2e_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const bool plots = io::gnuplot_available();
    const MeasuredRun a = measured_run(dir, "a", 2.0), b = measured_run(dir, "b", 3.0);
    for (const auto& [r, label] : {std::pair{a, "cpu-A"}, std::pair{b, "cpu-B"}}) {
        std::string cmd = "energy integrate " + r.log.string() + " --markers " + r.markers.string() + " --align auto --platform " + label +
                          " --json " + r.json.string() + " --csv " + r.json.string() + ".csv";
        if (plots) cmd += " --plot " + r.json.string() + ".png";
        ASSERT_EQ(run(cmd), 0) << cmd;
    }
    // The energies of run A match the power the log was built with.
    const auto ja = nlohmann::json::parse(slurp(a.json));
    EXPECT_EQ(ja["frames"].size(), 12u);
    EXPECT_NEAR(ja["idle"]["w"].get<double>(), 1.5, 0.05);
    for (const auto& f : ja["frames"]) {
        const double len = f["end_s"].get<double>() - f["start_s"].get<double>();
        EXPECT_NEAR(f["net_j"].get<double>(), 2.0 * len, 2.0 * 2 * 1e-3 + f["error_j"].get<double>()) << f.dump();
    }
    const fs::path out = dir / "compare";
    std::string cmd = "energy compare " + a.json.string() + " " + b.json.string() + " -o " + out.string() + (plots ? "" : " --no-plots");
    ASSERT_EQ(run(cmd), 0) << cmd;
    const std::string md = slurp(out / "tables.md");
    for (const char* h : {"Table 1", "Table 2", "Table 3", "cpu-A", "cpu-B"}) EXPECT_NE(md.find(h), std::string::npos) << h;
    for (const char* f : {"table1_energy.csv", "table2_shapiro_wilk.csv", "table3_t_tests.csv"}) EXPECT_TRUE(fs::exists(out / f)) << f;
    const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
    EXPECT_EQ(s["platforms"].size(), 2u);
    EXPECT_EQ(s["pairs"].size(), 1u);
    EXPECT_EQ(s["inputs"][0]["sha256"].get<std::string>().size(), 64u);
    EXPECT_EQ(s["inputs"][0]["log"]["sha256"].get<std::string>().size(), 64u);
    if (plots) {
        for (const char* f : {"energy_histograms.png", "energy_boxplot.png", "frame_time_boxplot.png"}) EXPECT_GT(fs::file_size(out / f), 1000u) << f;
        EXPECT_GT(fs::file_size(a.json.string() + ".png"), 1000u);
    } else {
        std::cout << "gnuplot not on PATH: plots not checked\n";
    }
    // Bad input fails with a message, not a crash.
    EXPECT_NE(run("energy compare " + a.log.string() + " -o " + out.string()), 0);
    EXPECT_NE(run("energy integrate " + a.log.string() + " --markers " + a.markers.string()), 0);  // relative log, realtime markers, no alignment
    fs::remove_all(dir);
}

}  // namespace
}  // namespace trn::energy
