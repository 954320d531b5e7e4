// The log formats added for issue 16: nvidia-smi without a header and with the index first,
// powerstat, turbostat, UNIX-epoch seconds read as absolute time, and the catalog that
// `trnkit energy formats` prints. Example logs live in fuzz/corpus/power_logs (also fuzz seeds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "../cli/cli_process.hpp"
#include "text_input.hpp"
#include "trn/energy/format_catalog.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::string example(const std::string& name) {
    std::ifstream in(std::string(TRN_POWER_LOG_EXAMPLES) + "/" + name);
    EXPECT_TRUE(in) << name;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string error_of(const std::string& text, const std::string& format, const ParseOptions& o = {}) {
    try {
        parse_power_log(text, "x.log", format, o);
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

const double t0_nvsmi = text::civil_to_unix(2024, 10, 30, 18, 42, 33.189);

TEST(Formats, NvidiaSmiWithoutHeader) {
    const PowerTrace tr = parse_power_log(example("nvidia-smi_noheader.csv"), "n.csv");
    EXPECT_EQ(tr.format, "nvidia-smi");
    ASSERT_EQ(tr.size(), 4u);
    EXPECT_NEAR(tr.t[0], t0_nvsmi, 1e-6);
    EXPECT_DOUBLE_EQ(tr.w[0], 22.89);
    EXPECT_DOUBLE_EQ(tr.w[2], 23.10);
    EXPECT_TRUE(tr.wall_clock);
    EXPECT_TRUE(tr.local_time);
}

TEST(Formats, NvidiaSmiIndexFirstWithAndWithoutHeader) {
    const PowerTrace h = parse_power_log(example("nvidia-smi_index_first.csv"), "h.csv");
    EXPECT_EQ(h.format, "nvidia-smi");
    ASSERT_EQ(h.size(), 3u);
    EXPECT_DOUBLE_EQ(h.w[1], 22.73);
    // Two GPUs interleaved, no header, nounits: the index field tells them apart.
    const std::string two = example("nvidia-smi_index_noheader_nounits.csv");
    const std::string why = error_of(two, "auto");
    EXPECT_NE(why.find("2 GPUs in the log (0, 1); pass gpu="), std::string::npos) << why;
    const PowerTrace g1 = parse_power_log(two, "two.csv", "auto", {{"gpu", "1"}});
    ASSERT_EQ(g1.size(), 3u);
    EXPECT_DOUBLE_EQ(g1.w[0], 51.20);
    EXPECT_NEAR(g1.t[0], t0_nvsmi + 0.001, 1e-6);
    // columns= names the fields of a headerless log the guess cannot read.
    const std::string many = "2024/10/30 18:42:33.189, 45, 71, 22.89\n2024/10/30 18:42:33.239, 46, 71, 22.73\n";
    EXPECT_NE(error_of(many, "nvidia-smi").find("x.log:1: no header, and the power field cannot be told"), std::string::npos) << error_of(many, "nvidia-smi");
    const PowerTrace named = parse_power_log(many, "m.csv", "nvidia-smi", {{"columns", "timestamp,utilization.gpu,temperature.gpu,power.draw"}});
    EXPECT_DOUBLE_EQ(named.w[1], 22.73);
}

TEST(Formats, Powerstat) {
    const std::string log = example("powerstat_rapl.txt");
    const PowerTrace tr = parse_power_log(log, "p.txt");
    EXPECT_EQ(tr.format, "powerstat");
    ASSERT_EQ(tr.size(), 5u);  // the summary after the dashes is not read
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
    EXPECT_FALSE(tr.wall_clock);
    EXPECT_DOUBLE_EQ(tr.t[0], 23 * 3600 + 59 * 60 + 57.0);
    EXPECT_DOUBLE_EQ(tr.t[3], 86400.0);  // past midnight: the next day
    EXPECT_DOUBLE_EQ(tr.w[2], 18.44);
    const PowerTrace dated = parse_power_log(log, "p.txt", "powerstat", {{"date", "2026-12-01"}});
    EXPECT_TRUE(dated.wall_clock && dated.local_time);
    EXPECT_DOUBLE_EQ(dated.t[4], text::civil_to_unix(2026, 12, 2, 0, 0, 1));
    EXPECT_NE(error_of(log, "powerstat", {{"column", "pkg-0"}}).find("x.log:4: header has no 'pkg-0' column"), std::string::npos);
    std::string cut = log;
    cut.replace(cut.find("18.61"), 5, "");
    EXPECT_NE(error_of(cut, "powerstat").find("x.log:8: expected 13 fields"), std::string::npos) << error_of(cut, "powerstat");
}

TEST(Formats, Turbostat) {
    const PowerTrace tr = parse_power_log(example("turbostat_per_cpu.txt"), "t.txt");
    EXPECT_EQ(tr.format, "turbostat");
    ASSERT_EQ(tr.size(), 3u);  // one summary row per interval, per-CPU rows skipped
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
    EXPECT_TRUE(tr.wall_clock);  // Time_Of_Day_Seconds is UNIX time
    EXPECT_FALSE(tr.local_time);
    EXPECT_DOUBLE_EQ(tr.t[1], 1764590401.002345);
    EXPECT_DOUBLE_EQ(tr.w[2], 12.84);
    const PowerTrace cores = parse_power_log(example("turbostat_per_cpu.txt"), "t.txt", "turbostat", {{"column", "CorWatt"}, {"interval_s", "1"}});
    EXPECT_DOUBLE_EQ(cores.w[0], 4.20);
    ASSERT_TRUE(cores.first_interval_start.has_value());
    EXPECT_DOUBLE_EQ(*cores.first_interval_start, 1764590399.002345);
    // --Summary without a time column: rows every interval_s from 0.
    const PowerTrace s = parse_power_log(example("turbostat_summary_no_time.txt"), "s.txt", "auto", {{"interval_s", "2"}});
    ASSERT_EQ(s.size(), 4u);
    EXPECT_DOUBLE_EQ(s.t[0], 2.0);
    EXPECT_DOUBLE_EQ(s.w[2], 25.40);
    EXPECT_DOUBLE_EQ(*s.first_interval_start, 0.0);
    const PowerTrace ram = parse_power_log(example("turbostat_summary_no_time.txt"), "s.txt", "turbostat", {{"column", "RAMWatt"}, {"interval_s", "5"}});
    EXPECT_DOUBLE_EQ(ram.w[2], 2.90);
    EXPECT_DOUBLE_EQ(ram.t[1], 10.0);
    // Without a time column or interval_s the interval is never assumed (issue 26; it was 5 s).
    EXPECT_NE(error_of(example("turbostat_summary_no_time.txt"), "turbostat").find("pass interval_s=SECONDS"), std::string::npos);
    EXPECT_NE(error_of("PkgWatt\n12.5\nabc\n", "turbostat", {{"interval_s", "1"}}).find("x.log:3: PkgWatt 'abc' is not a number"), std::string::npos);
}

TEST(Formats, UnixEpochSecondsAreAbsolute) {
    const PowerTrace tr = parse_power_log("time_s,power_mW\n1764590400.000,2000\n1764590400.010,2100\n1764590400.020,2050\n", "e.csv");
    EXPECT_TRUE(tr.wall_clock);
    EXPECT_FALSE(tr.local_time);
    const PowerTrace ms = parse_power_log("time_ms,power_mW\n1764590400000,2000\n1764590400010,2100\n", "e.csv");
    EXPECT_TRUE(ms.wall_clock);
    const PowerTrace rel = parse_power_log("time_s,power_mW\n0.000,2000\n0.010,2100\n", "r.csv");
    EXPECT_FALSE(rel.wall_clock);
}

TEST(Formats, CatalogNamesEveryFormatAndTheCommandPrintsIt) {
    const auto& cat = power_log_format_catalog();
    std::vector<std::string> names;
    for (const auto& f : cat) names.push_back(f.name);
    EXPECT_EQ(names, power_log_formats());
    for (const auto& f : cat) {
        EXPECT_FALSE(f.columns.empty() || f.units.empty() || f.example.empty() || f.options.empty()) << f.name;
    }
    const std::string text = format_catalog_text();
    for (const auto& n : names) EXPECT_NE(text.find("\n" + n + ": "), std::string::npos) << n;
    // The CLI command the "unrecognised" hint names exists and prints the catalog.
    const auto r = trn::test::run_trnkit("energy formats");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, text);
    EXPECT_NE(error_of("just one field\n", "auto").find("one of trnkit energy formats"), std::string::npos);
}

}  // namespace
}  // namespace trn::energy
