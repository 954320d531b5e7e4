// `trnkit energy bench|sample|integrate` as a user runs them (real processes), with the fake
// NVML library (board power follows the process's CPU use: 10 W + 40 W per busy core) and fake
// sysfs trees: the one-command bench on cpu and cpu-ref, its files reproducing through
// `energy integrate`, and every failing sampler named in one line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_process.hpp"
#include "trn/build_info.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;
using test::run_trnkit;

fs::path temp(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    return p;
}

nlohmann::json read_json(const fs::path& p) {
    std::ifstream f(p);
    return nlohmann::json::parse(f);
}

TEST(EnergyBenchCli, CpuAndCpuRefWithTheFakeNvmlSampler) {
    const fs::path out = temp("trn_bench_cli");
    const bool plots = io::gnuplot_available();
    const std::string cmd = "energy bench --source nvml:0:energy --nvml-lib " + std::string(FAKE_NVML) +
                            " -b cpu,cpu-ref --kernel sobel --size 480p --repeat 32 -k 6 --idle-ms 30 --lead-idle-ms 300 --period-ms 0.5 --min-samples 0"
                            " --platform fakebox -o " +
                            out.string() + (plots ? "" : " --no-plots");
    const auto r = run_trnkit(cmd);
    ASSERT_EQ(r.code, 0) << cmd << "\n" << r.output;
    const auto bench = read_json(out / "bench.json");
    EXPECT_EQ(bench["clock"], "monotonic");
    // Provenance (issue 13): which build wrote the bench and each run report.
    for (const auto& j : {bench, read_json(out / "run-cpu.json")}) {
        EXPECT_EQ(j.value("trnkit_version", ""), std::string(build_info().version));
        EXPECT_EQ(j.value("git_commit", ""), std::string(build_info().git_commit));
    }
    EXPECT_NE(bench["sampler"].get<std::string>().find("nvml:0:energy (Fake GPU"), std::string::npos);
    ASSERT_EQ(bench["rows"].size(), 2u);
    EXPECT_EQ(bench["rows"][0]["backend"], "cpu");
    EXPECT_EQ(bench["rows"][1]["backend"], "cpu-ref");
    for (const auto& row : bench["rows"]) {
        SCOPED_TRACE(row.dump());
        EXPECT_EQ(row["platform"], "fakebox");
        EXPECT_EQ(row["frames"], 6);
        EXPECT_EQ(row["calls_per_frame"], 32);
        // --min-samples 0: on a loaded 2-core machine the sampler thread can miss a whole 3 ms frame
        // (0..12 samples seen at load 15); the energy counter still puts every joule in some
        // interval, so the means below hold.
        EXPECT_EQ(row["usable"], 6);
        const double fps = row["frames_per_s"], ms = row["frame_ms"], gross = row["gross_j"], net = row["net_j"];
        const double idle = row["idle_w"], busy = row["busy_w"], bound = row["bound_j"];
        EXPECT_GT(fps, 0);
        EXPECT_NEAR(fps * ms, 1000, 1e-6);
        // Idle: 10 W plus the sampler thread's own CPU; busy: the frames' CPU share on top (a
        // share of a core only, on a machine loaded by other jobs).
        EXPECT_GT(idle, 9.5);
        EXPECT_LT(idle, 20);
        EXPECT_GT(busy, idle + 1);
        EXPECT_LT(busy, 10 + 40 * 64);
        EXPECT_NEAR(gross, busy * ms / 1000, 1e-9 + 1e-6 * gross);  // per call: both divided by the 32 calls
        EXPECT_GT(net, 0);
        EXPECT_LT(net, gross);
        EXPECT_NEAR(net, gross - idle * ms / 1000, 0.05 * gross);
        EXPECT_GE(bound, 0);
    }
    // cpu-ref (naive loops, one core) is slower than the optimized cpu backend.
    EXPECT_GT(bench["rows"][1]["frame_ms"].get<double>(), bench["rows"][0]["frame_ms"].get<double>());
    std::ifstream md(out / "bench.md");
    std::stringstream mds;
    mds << md.rdbuf();
    EXPECT_NE(mds.str().find("| fakebox | cpu-ref |"), std::string::npos) << mds.str();
    EXPECT_NE(r.output.find("| fakebox | cpu |"), std::string::npos) << r.output;  // the table on stdout
    for (const char* f : {"bench.csv", "power.log", "markers-cpu.csv", "markers-cpu-ref.csv", "run-cpu.json", "run-cpu-ref.json", ".trnkit-output"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    if (plots) {
        for (const char* f : {"bench_energy.png", "bench_speed.png", "trace-cpu.png", "trace-cpu-ref.png"}) EXPECT_GT(fs::file_size(out / f), 1000u) << f;
    }

    // The written log and markers give the same frames through the ordinary integrate command.
    const fs::path again = out / "again.json";
    const auto i = run_trnkit("energy integrate " + (out / "power.log").string() + " --markers " + (out / "markers-cpu-ref.csv").string() +
                              " --clock mono --json " + again.string());
    ASSERT_EQ(i.code, 0) << i.output;
    const auto a = read_json(again), b = read_json(out / "run-cpu-ref.json");
    ASSERT_EQ(a["frames"].size(), b["frames"].size());
    for (std::size_t k = 0; k < a["frames"].size(); ++k) EXPECT_DOUBLE_EQ(a["frames"][k]["gross_j"].get<double>(), b["frames"][k]["gross_j"].get<double>());
    // The run reports feed `energy compare` directly.
    const auto c = run_trnkit("energy compare " + (out / "run-cpu.json").string() + " " + (out / "run-cpu-ref.json").string() + " --no-plots -o " +
                              (out / "compare").string());
    EXPECT_EQ(c.code, 0) << c.output;
    EXPECT_NE(c.output.find("fakebox:cpu-ref/sobel/480p"), std::string::npos) << c.output;
    fs::remove_all(out);
}

// A fake hwmon ina226 at a constant 2.5 W: every frame's gross joules are exactly 2.5 W x its
// time and nothing is left above idle, so the row's energy and time columns are joined right.
TEST(EnergyBenchCli, ConstantHwmonPowerGivesPowerTimesFrameTime) {
    const fs::path out = temp("trn_bench_cli_hwmon"), sysfs = temp("trn_bench_sysfs");
    fs::create_directories(sysfs / "class/hwmon/hwmon0");
    std::ofstream(sysfs / "class/hwmon/hwmon0/name") << "ina226\n";
    std::ofstream(sysfs / "class/hwmon/hwmon0/power1_input") << "2500000\n";
    const auto r = run_trnkit("energy bench --source hwmon:ina226 --sysfs-root " + sysfs.string() +
                              " -b cpu-ref --size 480p --repeat 8 -k 4 --idle-ms 20 --lead-idle-ms 100 --period-ms 1 --min-samples 0 --no-plots -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto row = read_json(out / "bench.json")["rows"][0];
    EXPECT_EQ(row["backend"], "cpu-ref");
    EXPECT_EQ(row["usable"], 4) << row.dump();  // constant power: exact with any number of samples
    const double ms = row["frame_ms"], gross = row["gross_j"];
    EXPECT_NEAR(gross, 2.5 * ms / 1000, 1e-9 * gross);
    EXPECT_NEAR(row["net_j"].get<double>(), 0, 1e-9);
    EXPECT_NEAR(row["idle_w"].get<double>(), 2.5, 1e-9);
    fs::remove_all(out), fs::remove_all(sysfs);
}

TEST(EnergyBenchCli, FailingSamplersAreNamedBeforeAnyWork) {
    const fs::path out = temp("trn_bench_cli_fail");
    auto r = run_trnkit("energy bench --source nvml:0 --nvml-lib /nonexistent/libnvidia-ml.so.1 -b cpu -k 2 --no-plots -o " + out.string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("nvml: cannot load '/nonexistent/libnvidia-ml.so.1'"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing written when the sampler cannot start";
    r = run_trnkit("energy bench --source rapl:package-0 --sysfs-root /nonexistent-sysfs -b cpu -k 2 --no-plots -o " + out.string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("source 'rapl:package-0' not found under /nonexistent-sysfs"), std::string::npos) << r.output;
    r = run_trnkit("energy bench --source nvml:0:energy --nvml-lib " + std::string(FAKE_NVML_NO_ENERGY) + " -b cpu -k 2 --no-plots -o " + out.string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("no total energy counter"), std::string::npos) << r.output;
    r = run_trnkit("energy bench --source nvml:0 --nvml-lib " + std::string(FAKE_NVML) + " -b cpu -b cpu -k 2 --no-plots -o " + out.string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--backend cpu is given twice"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// Issue 45, class 4: a --platform that is not UTF-8 made the JSON writer fail (exit 2) after the
// bench had removed the previous run's files. It is refused up front, and those files stay.
TEST(EnergyBenchCli, APlatformThatIsNotUtf8IsRefusedBeforeThePreviousRunIsTouched) {
    const fs::path out = temp("trn_bench_cli_label"), sysfs = temp("trn_bench_sysfs_label");
    fs::create_directories(sysfs / "class/hwmon/hwmon0");
    std::ofstream(sysfs / "class/hwmon/hwmon0/name") << "ina226\n";
    std::ofstream(sysfs / "class/hwmon/hwmon0/power1_input") << "2500000\n";
    const std::string args = "energy bench --source hwmon:ina226 --sysfs-root " + sysfs.string() +
                             " -b cpu --size 480p -k 2 --idle-ms 5 --lead-idle-ms 20 --period-ms 1 --min-samples 0 --no-plots -o " + out.string();
    auto r = run_trnkit(args + " --platform first");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto before = fs::last_write_time(out / "bench.json");
    r = run_trnkit(args + " --platform \"$(printf 'tx2\\377')\"");  // printf: /bin/sh has no $'...'
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--platform 'tx2\\xff': byte 4 is not UTF-8"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    ASSERT_TRUE(fs::exists(out / "bench.json")) << "the previous run's files were removed";
    EXPECT_EQ(fs::last_write_time(out / "bench.json"), before);
    EXPECT_EQ(read_json(out / "bench.json")["rows"][0]["platform"], "first");
    fs::remove_all(out), fs::remove_all(sysfs);
}

TEST(EnergySampleCli, NvmlAndListing) {
    const fs::path log = temp("trn_sample_nvml.log");
    auto r = run_trnkit("energy sample --source nvml:0 --nvml-lib " + std::string(FAKE_NVML) + " --period-ms 5 --duration-s 0.1 -o " + log.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const PowerTrace tr = read_power_log(log.string());
    fs::remove(log);
    EXPECT_GE(tr.size(), 5u);  // 20 polls due; a loaded machine delays some
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);  // the counter, where the GPU has one
    EXPECT_TRUE(tr.wall_clock);
    // Mean power over the log: the counter's 10 W idle plus this process's little CPU. (Single
    // intervals can be off by the counter's 1 mJ step when two polls come close together.)
    ASSERT_TRUE(tr.first_interval_start);
    double joules = 0, t = *tr.first_interval_start;
    for (std::size_t i = 0; i < tr.size(); ++i) joules += tr.w[i] * (tr.t[i] - t), t = tr.t[i];
    const double mean_w = joules / (tr.t.back() - *tr.first_interval_start);
    EXPECT_GT(mean_w, 9.9);
    EXPECT_LT(mean_w, 10 + 40 * 64);
    r = run_trnkit("energy sample --list --sysfs-root /nonexistent-sysfs --nvml-lib " + std::string(FAKE_NVML));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("nvml:0 Fake GPU (CPU-driven) (board power, energy counter)"), std::string::npos) << r.output;
}

TEST(EnergyIntegrateCli, MinimalMarkersAndPmtMarkers) {
    const fs::path dir = temp("trn_integrate_markers");
    fs::create_directories(dir);
    // A relative-time log (3 W, 5 W inside [1, 2) s) and minimal markers on its clock.
    PowerTrace tr;
    tr.source = "rel", tr.format = "trnkit";
    for (int i = 0; i <= 3000; ++i) tr.t.push_back(i * 1e-3), tr.w.push_back(i >= 1000 && i < 2000 ? 5.0 : 3.0);
    std::ofstream(dir / "power.log") << format_trnkit_power(tr);
    std::ofstream(dir / "m.csv") << "frame,start_s,end_s\n0,1.0,2.0\n";
    auto r = run_trnkit("energy integrate " + (dir / "power.log").string() + " --markers " + (dir / "m.csv").string() + " --json " + (dir / "r.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    auto j = read_json(dir / "r.json");
    ASSERT_EQ(j["frames"].size(), 1u);
    EXPECT_NEAR(j["frames"][0]["gross_j"].get<double>(), 5.0, 0.003);
    EXPECT_EQ(j["config"]["clock"], "log");
    // No --markers: a log with PMT start/end markers supplies the frames; one without is refused.
    std::ofstream(dir / "pmt.log") << "timestamp gpu_instant\n100.00 2\n100.01 2\nM 0.015 \"start\"\n100.02 6\n100.03 6\n100.04 6\nM 0.045 \"end\"\n"
                                      "100.05 2\n100.06 2\n";
    r = run_trnkit("energy integrate " + (dir / "pmt.log").string() + " --json " + (dir / "p.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    j = read_json(dir / "p.json");
    ASSERT_EQ(j["frames"].size(), 1u);
    EXPECT_NEAR(j["frames"][0]["end_s"].get<double>() - j["frames"][0]["start_s"].get<double>(), 0.03, 1e-6);
    r = run_trnkit("energy integrate " + (dir / "power.log").string() + " --json " + (dir / "x.json").string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.output.find("no start/end markers of its own: give a marker file (--markers)"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace trn::energy
