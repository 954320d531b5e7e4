// Issue 26: power logs as they come from other people's machines. Each class of silent misread or
// needless refusal found on real logs is reproduced here on a small log written for the test.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "text_input.hpp"
#include "log_checks.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

using test::error_of;
using test::joules;
using test::mentions;

// 1. Decimal commas.
TEST(ForeignLogs, DecimalCommasAreReadOrRefusedNeverTruncated) {
    // ';' separator, comma decimals (a German logger): 30,3 W is 30.3 W.
    const PowerTrace semi = parse_power_log("time_s;power_W\n0;30,3\n1;30,7\n2;31,1\n", "s.csv");
    EXPECT_DOUBLE_EQ(semi.w[0], 30.3);
    EXPECT_TRUE(mentions(semi.notes, "decimal commas"));
    // ',' separator and every value with a decimal comma: twice the header's fields, read as pairs.
    const PowerTrace pairs = parse_power_log("time_s,power_W\n0,5,30,3\n1,5,30,7\n2,5,31,1\n", "p.csv");
    EXPECT_DOUBLE_EQ(pairs.t[0], 0.5);
    EXPECT_DOUBLE_EQ(pairs.w[1], 30.7);
    // ',' separator, some values without decimals: refused naming the line (used to read 30.0).
    const std::string why = error_of("time_s,power_W\n0,30,3\n1,30,7\n2,31\n");
    EXPECT_NE(why.find("x.log:2: 3 fields, but the header names 2"), std::string::npos) << why;
    EXPECT_NE(why.find("decimal commas"), std::string::npos) << why;
    // a quoted decimal comma under ',' is refused too
    EXPECT_NE(error_of("time_s,power_W\n0,\"30,3\"\n1,\"30,7\"\n").find("decimal comma"), std::string::npos);
    // one locale per file
    EXPECT_NE(error_of("time_s;power_W\n0;30,3\n1;30.7\n").find("one locale per file"), std::string::npos);
}

// 2. Units never guessed silently.
TEST(ForeignLogs, PowerUnitsFromNamesOrRefused) {
    const PowerTrace watts = parse_power_log("time_s,total_watts\n0,350\n1,360\n", "w.csv");
    EXPECT_DOUBLE_EQ(watts.w[0], 350) << "'total_watts' is in W (it used to be read as mW)";
    const std::string why = error_of("time_s,power\n0,350\n1,360\n");
    EXPECT_NE(why.find("power column 'power' has no unit in its name"), std::string::npos) << why;
    EXPECT_NE(why.find("power_unit="), std::string::npos) << why;
    EXPECT_DOUBLE_EQ(parse_power_log("time_s,power\n0,350\n1,360\n", "w.csv", "auto", {{"power_unit", "W"}}).w[1], 360);
    // pynvml per-GPU columns in W: two power columns, never one picked, never mW.
    const std::string gpus = "time_s,GPU0 [W],GPU1 [W]\n0,250,240\n1,260,250\n";
    EXPECT_NE(error_of(gpus).find("2 power columns ('GPU0 [W]', 'GPU1 [W]'): pass power=NAME"), std::string::npos) << error_of(gpus);
    EXPECT_DOUBLE_EQ(parse_power_log(gpus, "g.csv", "auto", {{"power", "sum"}}).w[0], 490);
    EXPECT_DOUBLE_EQ(parse_power_log(gpus, "g.csv", "auto", {{"power", "GPU1 [W]"}}).w[1], 250);
    const std::string bare = "time_s,GPU0,GPU1\n0,250,240\n1,260,250\n";
    EXPECT_NE(error_of(bare, "auto", {{"power", "GPU0"}}).find("has no unit in its name"), std::string::npos);
    // A power column without a unit beside V and I: its unit from the ratio, said in a note.
    const PowerTrace vi = parse_power_log("time_s,bus_V,current_mA,power\n0,5,400,2000\n1,5,420,2100\n", "v.csv", "auto", {{"use", "power"}});
    EXPECT_DOUBLE_EQ(vi.w[0], 2.0);
    EXPECT_TRUE(mentions(vi.notes, "mW, from its ratio to V x I"));
    // A current column without a unit and no way to tell: refused (it used to be taken as mA).
    EXPECT_NE(error_of("time_s,bus_V,current\n0,5,0.4\n1,5,0.42\n").find("current_unit="), std::string::npos);
}

// 3. The plausibility cap belongs to the source.
TEST(ForeignLogs, PlausibilityCapPerSourceSettableAndStated) {
    // A two-node GPU server's BMC totals of 10-14 kW are real (they were dropped at 10 kW).
    const PowerTrace node = parse_power_log("time_s,total_watts\n0,10500\n1,13900\n2,12000\n", "n.csv");
    EXPECT_EQ(node.size(), 3u);
    EXPECT_TRUE(node.warnings.empty());
    EXPECT_TRUE(mentions(node.notes, "plausibility cap +-20000 W"));
    // An INA rail (bus V and current) has a 1 kW cap; a 5 kW reading is a glitch.
    const PowerTrace rail = parse_power_log("time_s,bus_V,current_mA\n0,5,400\n1,5,1000000\n2,5,420\n", "r.csv");
    EXPECT_EQ(rail.size(), 2u);
    EXPECT_TRUE(mentions(rail.warnings, "beyond +-1000 W (the cap for an INA2xx/INA3221 rail"));
    // max_power_w= sets it, and the note says so.
    const PowerTrace capped = parse_power_log("time_s,total_watts\n0,10500\n1,13900\n2,12000\n", "n.csv", "auto", {{"max_power_w", "13000"}});
    EXPECT_EQ(capped.size(), 2u);
    EXPECT_TRUE(mentions(capped.notes, "+-13000 W"));
    EXPECT_TRUE(mentions(capped.warnings, "max_power_w"));
    // source= picks another source's cap
    EXPECT_EQ(parse_power_log("time_s,total_watts\n0,10500\n1,900\n2,800\n", "n.csv", "auto", {{"source", "gpu"}}).size(), 2u);
}

// 4. Sub-second tegrastats lines share 1 s stamps.
TEST(ForeignLogs, TegrastatsLinesSharingAStampArePlacedNotDropped) {
    std::string log;
    // 4 lines in the first (partial) second, then 10 a second for 3 s, then 3.
    auto line = [&](int sec, int mw) {
        char b[200];
        std::snprintf(b, sizeof b, "06-01-2025 10:00:%02d RAM 2000/7000MB CPU [5%%@1000] VDD_IN %dmW/%dmW VDD_CPU_GPU_CV 500mW/500mW\n", sec, mw, mw);
        log += b;
    };
    for (int k = 0; k < 4; ++k) line(0, 5000);
    for (int s = 1; s <= 3; ++s)
        for (int k = 0; k < 10; ++k) line(s, 5000);
    for (int k = 0; k < 3; ++k) line(4, 5000);
    const PowerTrace tr = parse_power_log(log, "t.log");
    ASSERT_EQ(tr.size(), 37u) << "no line dropped (33 of 37 were)";
    const double t0 = text::civil_to_unix(2025, 6, 1, 10, 0, 0);
    EXPECT_NEAR(tr.t[0], t0 + 0.6, 1e-6) << "the first second's lines are its last";
    EXPECT_NEAR(tr.t[4], t0 + 1.0, 1e-6);
    EXPECT_NEAR(tr.t[5], t0 + 1.1, 1e-6);
    EXPECT_NEAR(tr.t[36], t0 + 4.2, 1e-6);
    EXPECT_TRUE(mentions(tr.notes, "37 lines share their 1 s time stamp"));
    EXPECT_NEAR(joules(tr), 5.0 * 3.6, 1e-5);
    // interval_ms= is used for stamped lines too
    const PowerTrace half = parse_power_log(log, "t.log", "auto", {{"interval_ms", "50"}});
    EXPECT_NEAR(half.t[5] - half.t[4], 0.05, 1e-6);
}

// 5. Multi-GPU nvidia-smi logs.
TEST(ForeignLogs, NvidiaSmiSeveralGpus) {
    // 'index' 0 on every row (a wrapper's counter), a 'gpu' column that is not.
    std::string log = "timestamp, index, gpu, power.draw [W]\n";
    for (int s = 0; s < 3; ++s)
        for (int g = 0; g < 4; ++g) {
            char b[120];
            std::snprintf(b, sizeof b, "2024/10/30 18:42:%02d.%03d, 0, %d, %d.00 W\n", 30 + s, g, g, 100 + 10 * g + s);
            log += b;
        }
    const std::string why = error_of(log);
    EXPECT_NE(why.find("x.log:2: several GPUs in one log: 4 GPUs in the log (0, 1, 2, 3); pass gpu="), std::string::npos) << why;
    EXPECT_NE(why.find("gpu=all"), std::string::npos);
    const PowerTrace g3 = parse_power_log(log, "n.csv", "auto", {{"gpu", "3"}});
    ASSERT_EQ(g3.size(), 3u) << "gpu=3 used to find 0 usable samples";
    EXPECT_DOUBLE_EQ(g3.w[2], 132);
    const PowerTrace all = parse_power_log(log, "n.csv", "auto", {{"gpu", "all"}});
    ASSERT_EQ(all.size(), 3u);
    EXPECT_DOUBLE_EQ(all.w[0], 100 + 110 + 120 + 130);
    EXPECT_TRUE(mentions(all.notes, "sum of 4 GPUs"));
    EXPECT_NE(error_of(log, "auto", {{"gpu", "7"}}).find("gpu=7 is not in the log (4 GPUs"), std::string::npos);
    // No id column at all: the row order within each burst tells them apart.
    std::string order = "timestamp, power.draw [W]\n";
    for (int s = 0; s < 5; ++s) {
        char b[160];
        std::snprintf(b, sizeof b, "2024/10/30 18:42:%02d.100, %d.00 W\n2024/10/30 18:42:%02d.110, %d.00 W\n", 30 + s, 200 + s, 30 + s, 50 + s);
        order += b;
    }
    EXPECT_NE(error_of(order).find("2 GPUs in the log (0, 1); pass gpu=ID for one (told apart by their order"), std::string::npos) << error_of(order);
    EXPECT_DOUBLE_EQ(parse_power_log(order, "o.csv", "auto", {{"gpu", "1"}}).w[4], 54);
    EXPECT_DOUBLE_EQ(parse_power_log(order, "o.csv", "auto", {{"gpu", "all"}}).w[0], 250);
}

// 6. Formats users have.
TEST(ForeignLogs, PowerJoularCsv) {
    const std::string log = "Date,CPU Utilization,Total Power,CPU Power,GPU Power\n2024-05-02 10:15:01,0.05,12.4,11.1,1.3\n"
                            "2024-05-02 10:15:02,0.50,30.0,27.0,3.0\n2024-05-02 10:15:03,0.10,14.0,12.5,1.5\n";
    const PowerTrace tr = parse_power_log(log, "pj.csv");
    EXPECT_EQ(tr.format, "powerjoular");
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
    EXPECT_TRUE(tr.local_time);
    EXPECT_NEAR(joules(tr), 12.4 + 30.0 + 14.0, 1e-9);
    EXPECT_DOUBLE_EQ(parse_power_log(log, "pj.csv", "auto", {{"column", "CPU Power"}}).w[1], 27.0);
    const std::string cpu_only = "Date,CPU Utilization,CPU Power\n2024-05-02 10:15:01,0.05,11.1\n2024-05-02 10:15:02,0.50,27.0\n";
    EXPECT_DOUBLE_EQ(parse_power_log(cpu_only, "pj.csv").w[1], 27.0);
}

TEST(ForeignLogs, PerfStatIntervalText) {
    const std::string log = "#           time             counts unit events\n"
                            "     1.001048308              19.63 Joules power/energy-pkg/\n"
                            "     1.001048308               3.10 Joules power/energy-ram/\n"
                            "     2.002406532              20.01 Joules power/energy-pkg/\n"
                            "     2.002406532               3.20 Joules power/energy-ram/\n"
                            "     3.003000000      1,019.00 Joules power/energy-pkg/\n"
                            "     3.003000000      <not counted> Joules power/energy-ram/\n";
    const std::string why = error_of(log);
    EXPECT_NE(why.find("2 energy events in the log (power/energy-pkg/, power/energy-ram/): pass event=NAME"), std::string::npos) << why;
    const PowerTrace pkg = parse_power_log(log, "perf.txt", "auto", {{"event", "energy-pkg"}});
    EXPECT_EQ(pkg.format, "perf-stat");
    ASSERT_EQ(pkg.size(), 3u);
    EXPECT_NEAR(pkg.w[0], 19.63 / 1.001048308, 1e-9);
    EXPECT_NEAR(pkg.w[2], 1019.0 / (3.003 - 2.002406532), 1e-6);
    const PowerTrace sum = parse_power_log(log.substr(0, log.find("     3.003")), "perf.txt", "auto", {{"event", "sum"}});
    EXPECT_NEAR(sum.w[1], (20.01 + 3.20) / (2.002406532 - 1.001048308), 1e-9);
    // -x; as the separator
    EXPECT_EQ(parse_power_log("1.0;19.63;Joules;power/energy-pkg/;1000;100.00;;\n2.0;19.60;Joules;power/energy-pkg/;1000;100.00;;\n", "p.txt").size(), 2u);
}

TEST(ForeignLogs, TurbostatBannerAndItsInterval) {
    std::string log = "turbostat version 2023.11.07 - Len Brown <lenb@kernel.org>\nKernel command line: BOOT_IMAGE=/vmlinuz root=/dev/sda1\n"
                      "CPUID(0): GenuineIntel 0x1b CPUID levels\n";
    for (int i = 0; i < 60; ++i) log += "cpu" + std::to_string(i) + ": MSR_IA32_ENERGY_PERF_BIAS: 0x00000006 (balanced)\n";
    log += "Avg_MHz\tBusy%\tPkgWatt\tRAMWatt\n12\t0.8\t10.50\t2.10\n15\t1.1\t11.00\t2.20\n";
    const std::string why = error_of(log);
    EXPECT_NE(why.find("no Time_Of_Day_Seconds column and no interval in the log"), std::string::npos) << why;
    EXPECT_NE(why.find("interval_s="), std::string::npos) << why;
    const PowerTrace tr = parse_power_log(log, "ts.txt", "auto", {{"interval_s", "2"}});
    EXPECT_EQ(tr.format, "turbostat");
    EXPECT_DOUBLE_EQ(tr.t[1], 4.0);
    EXPECT_NEAR(joules(tr), 2 * 10.5 + 2 * 11.0, 1e-9);
    // turbostat CMD prints the measured length after each summary: the interval from the file.
    const PowerTrace cmd = parse_power_log("turbostat version 2023.11.07 - Len Brown\nPkgWatt\n10.50\n10.003 sec\nPkgWatt\n11.00\n5.000 sec\n", "c.txt");
    ASSERT_EQ(cmd.size(), 2u);
    EXPECT_DOUBLE_EQ(cmd.t[1], 15.003);
    EXPECT_NEAR(joules(cmd), 10.5 * 10.003 + 11.0 * 5.0, 1e-9);
}

TEST(ForeignLogs, SemicolonAndSpaceAlignedLoggerCsv) {
    // a wall meter: ';', DD.MM.YYYY stamps, comma decimals, units in brackets
    const PowerTrace wall = parse_power_log("Datum;Zeit;Leistung [W]\n12.03.2024;10:00:01;119,7\n12.03.2024;10:00:02;121,3\n12.03.2024;10:00:03;120,1\n", "w.csv");
    EXPECT_EQ(wall.format, "ina219-csv");
    ASSERT_EQ(wall.size(), 3u);
    EXPECT_DOUBLE_EQ(wall.w[1], 121.3);
    EXPECT_NEAR(wall.t[0], text::civil_to_unix(2024, 3, 12, 10, 0, 1), 1e-6);
    // a Raspberry Pi INA226 logger printing an aligned table
    const PowerTrace pi = parse_power_log("time_s     bus_V   current_mA\n  0.000     5.02      412.0\n  0.100     5.01      455.5\n  0.200     5.02      430.1\n", "pi.txt");
    EXPECT_EQ(pi.format, "ina219-csv");
    ASSERT_EQ(pi.size(), 3u);
    EXPECT_NEAR(pi.w[1], 5.01 * 0.4555, 1e-12);
    // date and time as two space-separated fields under one 'timestamp' name
    const PowerTrace dt = parse_power_log("time power_W\n2024-03-12 10:00:01 20.5\n2024-03-12 10:00:02 21.5\n", "d.txt");
    ASSERT_EQ(dt.size(), 2u);
    EXPECT_DOUBLE_EQ(dt.w[1], 21.5);
}

TEST(ForeignLogs, NvidiaSmiHeaderWithoutTimestamps) {
    const std::string log = "power.draw [W]\n45.20 W\n46.10 W\n45.90 W\n";
    const std::string why = error_of(log);
    EXPECT_EQ(why.find("no header"), std::string::npos) << "it has one: " << why;
    EXPECT_NE(why.find("x.log:1: the header names no 'timestamp' column"), std::string::npos) << why;
    EXPECT_NE(why.find("interval_ms="), std::string::npos) << why;
    const PowerTrace tr = parse_power_log(log, "n.csv", "auto", {{"interval_ms", "100"}});
    EXPECT_EQ(tr.format, "nvidia-smi");
    ASSERT_EQ(tr.size(), 3u);
    EXPECT_DOUBLE_EQ(tr.t[2], 0.2);
    EXPECT_FALSE(tr.wall_clock);
}

// 7. Negative power.
TEST(ForeignLogs, NegativePowerWarnedOrRefused) {
    // A shunt can read negative (reverse current): kept, with a warning, not silently.
    const PowerTrace rail = parse_power_log("time_s,bus_V,current_mA\n0,5,-80\n1,5,-80\n2,5,-80\n", "r.csv");
    EXPECT_NEAR(joules(rail), -0.8, 1e-12);
    EXPECT_TRUE(mentions(rail.warnings, "3 negative power reading(s) kept as read"));
    const PowerTrace own = parse_power_log("# trnkit-power v1 kind=instant\nt_s,power_w\n0,-0.4\n1,-0.4\n", "o.log");
    EXPECT_TRUE(mentions(own.warnings, "negative power")) << "a constant -0.4 W log used to pass without a word";
    // A GPU cannot draw negative power: refused with file:line.
    const std::string why = error_of("timestamp, power.draw [W]\n2024/10/30 18:42:33.100, 20.00 W\n2024/10/30 18:42:33.200, -0.40 W\n");
    EXPECT_NE(why.find("x.log:3: negative power -0.4 W, which a GPU board cannot draw"), std::string::npos) << why;
    EXPECT_NE(error_of("1.0,-0.50,Joules,power/energy-pkg/,1,100.00,,\n2.0,1.0,Joules,power/energy-pkg/,1,100.00,,\n").find("cannot draw"), std::string::npos);
}

}  // namespace
}  // namespace trn::energy
