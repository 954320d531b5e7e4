// `energy compare` given the same run twice (the same file, a copy under another name, or two
// reports of one measurement) refuses, naming both arguments, instead of doubling n.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_process.hpp"
#include "synthetic_run.hpp"
#include "trn/energy/compare.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

RunReport measured(double busy_w) {
    const auto tl = test::make_timeline(8, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    RunReport r = integrate_run(test::sample_trace(tl.markers, test::TraceClock{0, 0, ref}, ref - 0.1, ref + 2, 1e-3, 2.0, busy_w, 0, true), tl.markers,
                                IntegrateRequest{});
    r.log_path = "power.log", r.log_sha256 = std::string(64, busy_w > 2.5 ? 'a' : 'b');
    r.markers_path = "markers.csv", r.markers_sha256 = std::string(64, 'c');
    return r;
}

std::string refusal(const std::vector<RunInput>& in) {
    try {
        compare_runs(in, CompareOptions{});
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

TEST(CompareRepeats, SameReportOrSameMeasurementIsRefused) {
    const RunReport a = measured(3.0), b = measured(2.2);
    EXPECT_EQ(refusal({{"a.json", "1111", a}, {"b.json", "2222", b}}), "");
    std::string why = refusal({{"a.json", "1111", a}, {"b.json", "2222", b}, {"copy.json", "1111", a}});
    EXPECT_NE(why.find("a.json and copy.json are the same run report"), std::string::npos) << why;
    // A re-integration of the same log and markers (another file, other options) is the same measurement.
    RunReport again = a;
    again.platform = "relabelled";
    why = refusal({{"a.json", "1111", a}, {"again.json", "3333", again}});
    EXPECT_NE(why.find("a.json and again.json integrate the same measurement"), std::string::npos) << why;
}

TEST(CompareRepeats, CliRefusesTheSameFileTwiceAndACopy) {
    const fs::path dir = fs::temp_directory_path() / ("trn_compare_repeats_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string(), copy = (dir / "copy.json").string();
    std::ofstream(a) << run_report_json(measured(3.0));
    std::ofstream(b) << run_report_json(measured(2.2));
    fs::copy_file(a, copy);
    const auto ok = trn::test::run_trnkit("energy compare " + a + " " + b + " --no-plots -o " + (dir / "ok").string());
    EXPECT_EQ(ok.code, 0) << ok.output;
    for (const std::string& second : {a, copy}) {
        const auto r = trn::test::run_trnkit("energy compare " + a + " " + b + " " + second + " --no-plots -o " + (dir / "out").string());
        EXPECT_NE(r.code, 0) << r.output;
        EXPECT_NE(r.output.find(a + " and " + second + " are the same run report"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "out" / "tables.md"));
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace trn::energy
