// Every file in the shared powerlogs folder either parses (with sanity checks on the values) or
// is refused with a message naming file:line and why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "trn/error.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
#include "../common/shared_data.hpp"

using namespace trn::energy;

namespace {

std::string powerlogs() {
    const std::string p = trn::test::shared_data("powerlogs");
    return !p.empty() && std::filesystem::is_directory(p) ? p : "";
}

#define NEED_LOGS()                                                                                   \
    const std::string dir = powerlogs();                                                              \
    if (dir.empty()) GTEST_SKIP() << "TRN_SHARED_DATA/powerlogs not found: real power logs unavailable"

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

PowerTrace load(const std::string& dir, const std::string& rel, ParseOptions o = {}, const std::string& format = "auto") {
    return read_power_log(dir + "/" + rel, format, o);
}

std::string refusal(const std::string& dir, const std::string& rel, ParseOptions o = {}, const std::string& format = "auto") {
    try {
        load(dir, rel, o, format);
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

double mean_w(const PowerTrace& t) {
    double s = 0;
    for (double w : t.w) s += w;
    return s / static_cast<double>(t.size());
}

bool has_note(const PowerTrace& t, const std::string& part) {
    for (const auto& n : t.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(RealLogs, RaplToolsCsvIntegratesToThePowerLogTotal) {
    NEED_LOGS();
    const PowerTrace t = load(dir, "ina3221-hwmon-rapl/franciscoknebel_rapl-tools_Zill_O0_1e7_rapl.csv");
    EXPECT_EQ(t.format, "rapl-tools");
    const double oracle = parse_rapl_tools_total_energy(slurp(dir + "/ina3221-hwmon-rapl/franciscoknebel_rapl-tools_Zill_O0_1e7_power.log"), "power.log");
    EXPECT_DOUBLE_EQ(oracle, 276.734);
    const IntervalEnergy e = integrate_interval(t, 0.0, t.t.back());
    ASSERT_TRUE(e.covered);
    // The CSV ends at ~19.4 s while the summary covers 19.4484 s: allow 1 %.
    EXPECT_NEAR(e.energy_j, oracle, 0.01 * oracle) << "integrated " << e.energy_j << " J";
}

TEST(RealLogs, PowerLogSummaryIsRefusedAsATrace) {
    NEED_LOGS();
    const std::string why = refusal(dir, "ina3221-hwmon-rapl/franciscoknebel_rapl-tools_Zill_O0_1e7_power.log");
    EXPECT_NE(why.find("power.log:"), std::string::npos) << why;
    EXPECT_NE(why.find("not a power trace"), std::string::npos) << why;
}

TEST(RealLogs, ChargerFreeTextIsRefused) {
    NEED_LOGS();
    const std::string why = refusal(dir, "ina3221-hwmon-rapl/slymak_rpi_ina3221+ina219_output4charge.log");
    EXPECT_NE(why.find("output4charge.log:1:"), std::string::npos) << why;
    EXPECT_NE(why.find("no time stamps"), std::string::npos) << why;
}

TEST(RealLogs, PerfStatJoulesPerInterval) {
    NEED_LOGS();
    const PowerTrace t = load(dir, "ina3221-hwmon-rapl/peakler_cloudlab-c220g1_perfstat_I1000_energy-pkg.txt");
    EXPECT_EQ(t.size(), 30u);
    EXPECT_EQ(t.kind, SampleKind::IntervalMean);
    EXPECT_NEAR(t.w.front(), 19.63 / 1.001048308, 1e-9);
    const IntervalEnergy e = integrate_interval(t, 0, t.t.back());
    // The sum of the printed joules, 30 intervals of ~19-21 J.
    EXPECT_GT(e.energy_j, 30 * 19.0);
    EXPECT_LT(e.energy_j, 30 * 21.0);
}

TEST(RealLogs, HwmonRecordsKeepOnlyRecordsWithValues) {
    NEED_LOGS();
    const PowerTrace t = load(dir, "ina3221-hwmon-rapl/pablouc_jetson_ina3221_hwmon_powerConsumption.txt");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_NEAR(t.w[0], 0.856 * 4.944, 1e-9);
    EXPECT_TRUE(has_note(t, "dropped 3 row(s): record without current/voltage values")) << t.notes.front();
    // "Fr 20. Okt 17:52:28 CEST 2023" = 15:52:28 UTC
    EXPECT_DOUBLE_EQ(t.t[0], 1697817148.0);
}

TEST(RealLogs, Ina219AnandRefusedAtTheLoggerRestartAndParsedBeforeIt) {
    NEED_LOGS();
    const std::string rel = "ina219/anand2532_rpi4_ina219_2026-03-18_first5000.csv";
    // At line 500 the time steps back from 12:17:28 to 12:15:03 (a second logger run appended).
    const std::string why = refusal(dir, rel);
    EXPECT_NE(why.find("first5000.csv:500: time goes backwards"), std::string::npos) << why;
    std::string text = slurp(dir + "/" + rel);
    std::size_t cut = 0;
    for (int line = 0; line < 499; ++line) cut = text.find('\n', cut) + 1;
    const PowerTrace t = parse_ina219_csv(text.substr(0, cut), "first-run");
    EXPECT_EQ(t.size(), 498u);
    EXPECT_TRUE(t.wall_clock);
    EXPECT_NEAR(t.w[0], 10.788 * -0.3e-3, 1e-12);
    EXPECT_TRUE(has_note(t, "logger unit bug")) << t.notes.size();
    EXPECT_TRUE(has_note(t, "negative power"));
}

TEST(RealLogs, Ina219GreenroomNeedsAColumnMap) {
    NEED_LOGS();
    const std::string rel = "ina219/gvsu_greenroom_rpi_2021-09-20_13-14_power_data.csv";
    const std::string why = refusal(dir, rel);
    EXPECT_NE(why.find("power_data.csv:1: no header row"), std::string::npos) << why;
    const PowerTrace t = load(dir, rel, {{"columns", "index,sensor,bus_V,current_mA,power_W"}, {"period_s", "5"}});
    EXPECT_EQ(t.size(), 61u);
    EXPECT_DOUBLE_EQ(t.t[1] - t.t[0], 5.0);
    EXPECT_NEAR(t.w[0], 9.124 * 43.10131534775842e-3, 1e-9);
}

TEST(RealLogs, Ina219TuplesInSeconds) {
    NEED_LOGS();
    const PowerTrace t = load(dir, "ina219/juliusr91_odroid_data1_seconds.txt");
    EXPECT_GT(t.size(), 3000u);
    EXPECT_LT(std::abs(mean_w(t)), 0.5);  // ~11 V with near-zero current
}

TEST(RealLogs, Ina219TicksRefusedWithoutPeriodAndUnwrappedWithIt) {
    NEED_LOGS();
    const std::string rel = "ina219/juliusr91_odroid_data1_ticks.txt";
    const std::string why = refusal(dir, rel);
    EXPECT_NE(why.find("ticks.txt:"), std::string::npos) << why;
    EXPECT_NE(why.find("tick_period_s"), std::string::npos) << why;
    const PowerTrace t = load(dir, rel, {{"tick_period_s", "16e-6"}});  // 16 MHz / 256
    EXPECT_TRUE(has_note(t, "all-zero sentinel row"));
    EXPECT_TRUE(has_note(t, "above max_bus_v"));
    EXPECT_GT(mean_w(t), 1.0);
    EXPECT_LT(mean_w(t), 3.0);
    const SamplingReport s = describe_sampling(t);
    EXPECT_NEAR(s.median_dt_s, 81 * 16e-6, 2 * 16e-6);
}

TEST(RealLogs, NvidiaSmiFiles) {
    NEED_LOGS();
    const PowerTrace flame = load(dir, "nvidia-smi/pranavdani_flame_timestamp_powerdraw_lms50.csv");
    EXPECT_EQ(flame.size(), 73u);
    EXPECT_NEAR(flame.w[0], 22.89, 1e-12);
    EXPECT_NEAR(describe_sampling(flame).median_dt_s, 0.05, 0.005);

    const PowerTrace h100 = load(dir, "nvidia-smi/yqg9651_h100-pcie_fp16_half_allzero.csv");
    EXPECT_EQ(h100.quantity, "power.draw.instant");
    EXPECT_GT(describe_sampling(h100).stale_repeats, 10u);
    EXPECT_NEAR(h100.w[0], 47.24, 1e-12);

    const PowerTrace gtx = load(dir, "nvidia-smi/rdrigomachado_gtx1650_gpu_power.csv");
    EXPECT_NEAR(gtx.w[0], 19.46, 1e-12);

    const std::string why = refusal(dir, "nvidia-smi/mscdissertation_2xgtx1080ti_nounits_QQP_64_15m.csv");
    EXPECT_NE(why.find("15m.csv:"), std::string::npos) << why;
    EXPECT_NE(why.find("several GPUs"), std::string::npos) << why;
}

TEST(RealLogs, PmtDumpsWithMarkers) {
    NEED_LOGS();
    const PowerTrace nvml = load(dir, "pmt/nlesc_ps3results_rtx4000ada_pmt-nvml.log");
    EXPECT_EQ(nvml.quantity, "gpu_instant");
    ASSERT_EQ(nvml.markers.size(), 8u);
    const auto frames = intervals_from_trace_markers(nvml);
    ASSERT_EQ(frames.size(), 4u);
    const RunEnergy run = integrate_frames(nvml, frames);
    EXPECT_EQ(run.usable(), 4u);
    for (const auto& f : run.frames) {
        EXPECT_GT(f.gross_j / f.duration(), run.idle_w) << "a busy frame draws more than idle";
        EXPECT_FALSE(std::isnan(f.net_j));
    }
    const PowerTrace rocm = load(dir, "pmt/nlesc_ps3results_w7700_pmt-rocm.log");
    EXPECT_EQ(rocm.resolution_w, 1.0);
    EXPECT_EQ(rocm.markers.size(), 8u);
    EXPECT_NEAR(describe_sampling(rocm).median_dt_s, 0.002, 0.0006);
}

TEST(RealLogs, TegrastatsGenerations) {
    NEED_LOGS();
    const PowerTrace nano = load(dir, "tegrastats/sumantbagri_jetson-nano_tegrastats.txt");
    EXPECT_EQ(nano.quantity, "POM_5V_IN (input rail)");
    EXPECT_NEAR(nano.w[0], 0.920, 1e-12);
    EXPECT_TRUE(has_note(nano, "no time stamps"));
    const PowerTrace tx2 = load(dir, "tegrastats/ssaraff98_tx2_sample_log.txt");
    EXPECT_NEAR(tx2.w[0], 1.840, 1e-12);
    const PowerTrace prompt = load(dir, "tegrastats/putmotorsport_tx2_tegrastats_with_prompt.log");
    EXPECT_EQ(prompt.size(), 2u);
    EXPECT_NEAR(prompt.w[0], 3.566, 1e-12);
    const PowerTrace xavier = load(dir, "tegrastats/bjgeiser_xaviernx-class_tegrastats.log");
    EXPECT_TRUE(xavier.wall_clock);
    EXPECT_NEAR(xavier.w[0], 5.542, 1e-12);
    EXPECT_EQ(describe_sampling(xavier).gaps, 0u);  // one skipped second is 2 s < 3 x median
    EXPECT_NEAR(*std::max_element(xavier.w.begin(), xavier.w.end()), 13.7, 0.5);
    const PowerTrace orin = load(dir, "tegrastats/hanner123_agx-orin-64gb_tegrastats.log");
    EXPECT_NE(orin.quantity.find("sum of all rails"), std::string::npos);
    EXPECT_NEAR(orin.w[0], 2.798 + 0.799 + 3.315, 1e-9);
}

TEST(RealLogs, EveryFileParsesOrIsRefusedWithFileAndLine) {
    NEED_LOGS();
    std::size_t files = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file() || e.path().filename() == "SOURCES.md") continue;
        ++files;
        try {
            const PowerTrace t = read_power_log(e.path().string());
            validate_trace(t);
            for (double w : t.w) ASSERT_TRUE(std::isfinite(w)) << e.path();
        } catch (const trn::Error& err) {
            const std::string msg = err.what();
            EXPECT_EQ(msg.rfind(e.path().string(), 0), 0u) << "message must start with the file: " << msg;
        }
    }
    EXPECT_EQ(files, 20u);
}
