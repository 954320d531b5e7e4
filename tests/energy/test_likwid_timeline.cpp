// likwid-perfctr's timeline mode (-t), registered once in power_formats.def: rows of
// "<group> <count> <threads> <runtime> <values...>", metric-major, read as interval means of the
// chosen metric summed over the hardware threads.
#include <gtest/gtest.h>

#include <string>

#include "log_checks.hpp"

namespace trn::energy {
namespace {

using test::error_of;

// The ENERGY group on two hardware threads of one socket: the socket's RAPL metrics are counted on
// thread 0, thread 1 shows 0. Rows every 0.5 s; Energy [J] = Power [W] x 0.5 s.
const double kPower[] = {12.2, 30.4, 18.0};
// header_sep 0: no header (only likwid's stderr kept); '|' as likwid prints it to a terminal, ','
// with -O. Rows are space-separated on stderr, ','-separated with -O.
std::string timeline(char row_sep, char header_sep) {
    auto join = [](std::initializer_list<std::string> f, char sep) {
        std::string line;
        for (const auto& x : f) line += (line.empty() ? "" : std::string(1, sep)) + x;
        return line + "\n";
    };
    std::string s;
    if (header_sep) {
        s += join({"# HWThreads", "0", "1"}, header_sep);
        s += join({"# GID", "MetricsCount", "CpuCount", "Total runtime [s]", "Runtime (RDTSC) [s]", "Energy [J]", "Power [W]"}, header_sep);
    }
    for (int i = 0; i < 3; ++i) {
        const std::string t = std::to_string(0.5 * (i + 1)), p = std::to_string(kPower[i]), e = std::to_string(kPower[i] * 0.5);
        s += join({"1", "3", "2", t, "0.5", "0.5", e, "0", p, "0"}, row_sep);
    }
    return s;
}

TEST(LikwidTimeline, PowerOfTheEnergyGroupSummedOverThreadsAsIntervalMeans) {
    for (const auto& [rows, header] : {std::pair{' ', '|'}, std::pair{',', ','}}) {
        SCOPED_TRACE(std::string("rows '") + rows + "', header '" + header + "'");
        const std::string text = timeline(rows, header);
        EXPECT_EQ(detect_power_log_format(text, "l.log"), "likwid-timeline");
        const PowerTrace tr = parse_power_log(text, "l.log");
        ASSERT_EQ(tr.size(), 3u);
        EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(tr.w[i], kPower[i], 1e-9);
        EXPECT_NEAR(test::joules(tr), 0.5 * (kPower[0] + kPower[1] + kPower[2]), 1e-9);  // the first interval starts at 0
        EXPECT_NE(tr.quantity.find("Power [W] summed over 2 hardware thread(s)"), std::string::npos) << tr.quantity;
    }
    // An energy metric over each interval gives the same power.
    const PowerTrace e = parse_power_log(timeline(' ', '|'), "l.log", "auto", {{"metric", "Energy [J]"}});
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.w[i], kPower[i], 1e-6);
}

TEST(LikwidTimeline, WithoutTheHeaderTheMetricMustBeNamed) {
    const std::string bare = timeline(' ', 0);
    EXPECT_EQ(detect_power_log_format(bare, "l.log"), "likwid-timeline");
    const std::string e = error_of(bare);
    EXPECT_NE(e.find("x.log:1: a likwid-perfctr timeline without its '# GID|MetricsCount|...' header"), std::string::npos) << e;
    EXPECT_NE(e.find("pass metric=N"), std::string::npos) << e;
    const PowerTrace tr = parse_power_log(bare, "l.log", "auto", {{"metric", "3"}});
    EXPECT_NEAR(tr.w[1], kPower[1], 1e-9);
    EXPECT_NE(error_of(bare, "auto", {{"metric", "4"}}).find("metric='4': without likwid's '# GID|...' header give the metric's number, 1..3"),
              std::string::npos);
}

TEST(LikwidTimeline, OtherGroupsAndNonPowerMetricsAreRefusedNamingTheOption) {
    std::string two = timeline(' ', '|');
    two += "2 3 2 2.0 0.5 0.5 1 0 2 0\n";
    EXPECT_NE(error_of(two).find("x.log:6: rows of several groups (likwid switches groups with -T): pass group=N"), std::string::npos)
        << error_of(two);
    EXPECT_EQ(parse_power_log(two, "l.log", "auto", {{"group", "1"}}).size(), 3u);
    EXPECT_NE(error_of(timeline(' ', '|'), "auto", {{"metric", "Runtime (RDTSC) [s]"}}).find("is not a power [W] or energy [J] metric"),
              std::string::npos);
    EXPECT_NE(error_of(timeline(' ', '|'), "auto", {{"metric", "Power DRAM [W]"}}).find("no metric 'Power DRAM [W]' in the header"),
              std::string::npos);
    // a CPU package cannot draw negative power
    std::string neg = timeline(' ', '|');
    neg.replace(neg.rfind("18.000000"), 9, "-18.00000");
    EXPECT_NE(error_of(neg).find("negative"), std::string::npos) << error_of(neg);
}

// The example in the fuzz corpus (four threads, eight metrics, stdout header and stderr rows in one
// file) reads through auto: the package power of thread 0, the other threads' 0 adding nothing.
TEST(LikwidTimeline, TheCorpusExampleReads) {
    const PowerTrace tr = read_power_log(std::string(TRN_POWER_LOG_EXAMPLES) + "/likwid_perfctr_timeline.txt");
    EXPECT_EQ(tr.format, "likwid-timeline");
    ASSERT_EQ(tr.size(), 4u);
    EXPECT_NEAR(tr.w[1], 29.7158, 1e-9);
    EXPECT_NEAR(test::joules(tr), 0.500811 * 12.9215 + (1.001632 - 0.500811) * 29.7158 + (1.502447 - 1.001632) * 29.8539 +
                                      (2.003265 - 1.502447) * 12.9832,
                1e-9);
}

}  // namespace
}  // namespace trn::energy
