// Issue 46: energy logs, third round. Each silent misread or misleading refusal found on the second
// set of real logs is reproduced here on a small log written for the test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <unistd.h>
#include <string>

#include <filesystem>
#include <fstream>

#include "../cli/cli_process.hpp"
#include "sources/raspberry_pi/pi_pmic.hpp"
#include "log_checks.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/energy/power_sampler.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_summaries.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

using test::error_of;
using test::joules;
using test::mentions;

// Item 4: a header's unit is evidence, not truth.
TEST(UnitsAgainstSource, MilliwattHeaderOverWattValuesIsRefusedNamingBothReadings) {
    // A Raspberry Pi 5 PMIC log: the header says mW, the values are watts (3.3-9.2).
    const std::string pi5 = "time_s,Power (mW)\n0,3.3\n1,5.1\n2,9.2\n3,4.0\n";
    const std::string why = error_of(pi5);
    EXPECT_NE(why.find("x.log: power column 'Power (mW)' says mW"), std::string::npos) << why;
    EXPECT_NE(why.find("0.0033 to 0.0092 W"), std::string::npos) << why;
    EXPECT_NE(why.find("in W they would be 3.3 to 9.2 W"), std::string::npos) << why;
    EXPECT_NE(why.find("power_unit=W"), std::string::npos) << why;
    EXPECT_NE(why.find("power_unit=mW"), std::string::npos) << why;
    // The option settles it either way.
    const PowerTrace w = parse_power_log(pi5, "pi5.csv", "auto", {{"power_unit", "W"}});
    EXPECT_DOUBLE_EQ(w.w[2], 9.2);
    EXPECT_NEAR(joules(w), (3.3 + 5.1) / 2 + (5.1 + 9.2) / 2 + (9.2 + 4.0) / 2, 1e-9);
    const PowerTrace mw = parse_power_log(pi5, "pi5.csv", "auto", {{"power_unit", "mW"}});
    EXPECT_DOUBLE_EQ(mw.w[2], 9.2e-3);
    // A rail (a sensor board) may draw milliwatts: source=rail keeps the header's unit.
    EXPECT_DOUBLE_EQ(parse_power_log(pi5, "pi5.csv", "auto", {{"source", "rail"}}).w[0], 3.3e-3);
    // Milliwatts that are milliwatts of a computer pass.
    EXPECT_DOUBLE_EQ(parse_power_log("time_s,Power (mW)\n0,3300\n1,5100\n", "ok.csv").w[0], 3.3);
}

TEST(UnitsAgainstSource, KilowattHeaderOverAUsbDeviceIsRefused) {
    // A USB device cannot draw kilowatts: the values are watts.
    const std::string usb = "time_s,power_kW\n0,2.5\n1,4.8\n2,5.1\n";
    const std::string why = error_of(usb, "ina219-csv", {{"source", "usb"}});
    EXPECT_NE(why.find("says kW"), std::string::npos) << why;
    EXPECT_NE(why.find("more than a USB-powered device"), std::string::npos) << why;
    EXPECT_NE(why.find("in W they would be 2.5 to 5.1 W"), std::string::npos) << why;
    EXPECT_DOUBLE_EQ(parse_power_log(usb, "u.csv", "ina219-csv", {{"source", "usb"}, {"power_unit", "W"}}).w[1], 4.8);
    // a USB meter's export (data-line voltages D+/D-) is a USB device without being told
    const std::string meter = "Time,Power (kW),Data+ (V),Data- (V)\n0,2.5,0.6,0.6\n1,4.8,0.6,0.6\n2,5.1,0.6,0.6\n";
    EXPECT_NE(error_of(meter).find("more than a USB-powered device"), std::string::npos) << error_of(meter);
    const PowerTrace vi = parse_power_log("Time,Voltage (V),Current (A),D+ (V),D- (V)\n0,5.1,0.5,0.6,0.6\n1,5.1,0.6,0.6,0.6\n", "m.csv");
    EXPECT_TRUE(mentions(vi.notes, "a USB-powered device")) << "source usb, cap 240 W";
}

// Item 3 (CodeCarbon): per-run summaries, never a trace, machines never summed.
const std::string kCodeCarbon =
    "timestamp,project_name,run_id,duration,emissions,emissions_rate,cpu_power,gpu_power,ram_power,cpu_energy,gpu_energy,ram_energy,"
    "energy_consumed,country_name,os,python_version,codecarbon_version,cpu_count,cpu_model,gpu_count,gpu_model,ram_total_size,tracking_mode\n"
    "2024-05-02T10:00:00,demo,r1,60.0,1e-05,1.6e-07,42.5,0,3.0,0.000708,0,0.00005,0.000758,Germany,Linux,3.11,2.3.4,8,\"Intel(R) Xeon(R), 2.1GHz\",0,,31.3,machine\n"
    "2024-05-02T10:00:05,demo,r2,30.0,1e-05,1.6e-07,150,250,3.0,0.00125,0.002083,0.000025,0.003358,Germany,Linux,3.11,2.3.4,16,AMD EPYC 7302,1,"
    "1 x NVIDIA A100,251.7,machine\n"
    "2024-05-02T10:10:00,demo,r3,60.0,1e-05,1.6e-07,42.5,0,3.0,0.000708,0,0.00005,0.000758,Germany,Linux,3.11,2.3.4,8,\"Intel(R) Xeon(R), 2.1GHz\",0,,31.3,machine\n";

TEST(CodeCarbon, RefusedAsATraceNamingTheRunsCommand) {
    EXPECT_EQ(detect_power_log_format(kCodeCarbon, "emissions.csv"), "codecarbon");
    const std::string why = error_of(kCodeCarbon);
    EXPECT_NE(why.find("x.log:1: a CodeCarbon emissions.csv: 3 run(s) on 2 machine(s)"), std::string::npos) << why;
    EXPECT_NE(why.find("not a power trace"), std::string::npos) << why;
    EXPECT_NE(why.find("trnkit energy runs x.log"), std::string::npos) << why;
    // power=sum over its power columns, the old misread, is refused the same way (format named or not)
    EXPECT_NE(error_of(kCodeCarbon, "auto", {{"power", "sum"}}).find("CodeCarbon"), std::string::npos);
}

TEST(CodeCarbon, RunsAndTheirJoulesPerMachine) {
    const RunSummaries s = parse_codecarbon_runs(kCodeCarbon, "emissions.csv");
    ASSERT_EQ(s.runs.size(), 3u);
    ASSERT_EQ(s.machines.size(), 2u);
    EXPECT_NEAR(s.runs[0].energy_j, 0.000758 * 3.6e6, 1e-9);  // kWh -> J
    EXPECT_NEAR(*s.runs[0].cpu_j, 0.000708 * 3.6e6, 1e-9);
    EXPECT_DOUBLE_EQ(s.runs[1].duration_s, 30.0);
    EXPECT_EQ(s.runs[1].run_id, "r2");
    EXPECT_EQ(s.runs[0].machine, s.runs[2].machine);  // the quoted cpu_model with a comma is one field
    EXPECT_NE(s.runs[0].machine, s.runs[1].machine);
    EXPECT_NEAR(s.machine_energy_j(s.machines[0]), 2 * 0.000758 * 3.6e6, 1e-9);  // r1 + r3, the 10 min gap not interpolated
    EXPECT_NEAR(s.machine_energy_j(s.machines[1]), 0.003358 * 3.6e6, 1e-9);
    EXPECT_TRUE(mentions(s.notes, "2 machines in one file"));
    EXPECT_TRUE(mentions(s.notes, "never summed across machines"));
    const std::string table = format_run_summaries(s);
    EXPECT_NE(table.find("3 run(s) on 2 machine(s)"), std::string::npos) << table;
    EXPECT_NE(table.find("machine 1: 2 run(s), 120 s measured, 5457.6 J"), std::string::npos) << table;
    // Bad rows name file:line.
    std::string bad = kCodeCarbon;
    bad.replace(bad.find(",0.003358,"), 10, ",-0.003358,");
    try {
        parse_codecarbon_runs(bad, "e.csv");
        ADD_FAILURE() << "a negative energy was accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("e.csv:3: energy_consumed (kWh) -0.003358 is negative"), std::string::npos) << e.what();
    }
}

// `trnkit energy runs` lists them; `energy inspect` refuses the file naming that command.
TEST(CodeCarbon, TheRunsCommandAndTheInspectRefusal) {
    const auto path = std::filesystem::temp_directory_path() / ("trn_emissions_" + std::to_string(::getpid()) + ".csv");
    std::ofstream(path) << kCodeCarbon;
    const auto runs = trn::test::run_trnkit("energy runs " + path.string());
    EXPECT_EQ(runs.code, 0) << runs.output;
    EXPECT_NE(runs.output.find("3 run(s) on 2 machine(s)"), std::string::npos) << runs.output;
    EXPECT_NE(runs.output.find("machine 2: 1 run(s), 30 s measured, 12088.8 J"), std::string::npos) << runs.output;
    const auto inspect = trn::test::run_trnkit("energy inspect " + path.string() + " --opt power=sum");
    EXPECT_NE(inspect.code, 0);
    EXPECT_NE(inspect.output.find("trnkit energy runs " + path.string()), std::string::npos) << inspect.output;
    std::filesystem::remove(path);
}

// Item 2: long ("tidy") logs split into series, never interleaved or summed silently.
// A rapl-trace-like log: one row per socket x domain per poll, power in W. Socket 0 package 20 W,
// socket 0 dram 5 W, socket 1 package 30 W, socket 1 dram 6 W.
std::string tidy_power_log(int polls) {
    std::string s = "time_s,socket,domain,power_W\n";
    for (int k = 0; k < polls; ++k) {
        const std::string t = std::to_string(k) + ".0";
        s += t + ",0,package," + std::to_string(20 + k % 2) + "\n";
        s += t + ",0,dram,5\n";
        s += t + ",1,package,30\n";
        s += t + ",1,dram,6\n";
    }
    return s;
}

TEST(LongFormLogs, SeveralSeriesAreRefusedUntilOneOrAllIsNamed) {
    const std::string log = tidy_power_log(5);
    const std::string why = error_of(log);
    EXPECT_NE(why.find("4 series in one long-form log"), std::string::npos) << why;
    EXPECT_NE(why.find("socket x domain"), std::string::npos) << why;
    EXPECT_NE(why.find("socket=1,domain=dram"), std::string::npos) << why;
    EXPECT_NE(why.find("series=all"), std::string::npos) << why;
    // one series
    const PowerTrace one = parse_power_log(log, "t.csv", "auto", {{"series", "socket=1,domain=package"}});
    ASSERT_EQ(one.size(), 5u);
    EXPECT_DOUBLE_EQ(one.w[0], 30);
    EXPECT_NEAR(joules(one), 4 * 30, 1e-9);
    // a selection that leaves two is refused, naming the sum
    const std::string two = error_of(log, "auto", {{"series", "domain=package"}});
    EXPECT_NE(two.find("leaves 2 series"), std::string::npos) << two;
    EXPECT_NE(two.find("series=sum:domain=package"), std::string::npos) << two;
    const PowerTrace pk = parse_power_log(log, "t.csv", "auto", {{"series", "sum:domain=package"}});
    EXPECT_DOUBLE_EQ(pk.w[0], 50);
    EXPECT_DOUBLE_EQ(pk.w[1], 51);
    // all four per poll: 61 W (62 W on odd polls), 5 polls, not a sawtooth of 20 samples
    const PowerTrace all = parse_power_log(log, "t.csv", "auto", {{"series", "all"}});
    ASSERT_EQ(all.size(), 5u);
    EXPECT_DOUBLE_EQ(all.w[0], 61);
    EXPECT_NEAR(joules(all), 61.5 * 4, 1e-9);
    EXPECT_TRUE(mentions(all.notes, "sum of series"));
    // unknown key or value
    EXPECT_NE(error_of(log, "auto", {{"series", "rack=1"}}).find("'rack' is not a key column"), std::string::npos);
    EXPECT_NE(error_of(log, "auto", {{"series", "domain=gpu"}}).find("matches none"), std::string::npos);
    // a phase label that changes in runs is not a series key: the log reads as one trace
    EXPECT_EQ(parse_power_log("time_s,phase,power_W\n0,idle,5\n1,idle,5\n2,idle,5\n3,busy,9\n4,busy,9\n5,busy,9\n6,idle,5\n7,idle,5\n", "ph.csv").size(), 8u);
    // a log with one series (a constant text column) reads as before
    EXPECT_EQ(parse_power_log("time_s,sensor,power_W\n0,INA219,5\n1,INA219,6\n2,INA219,7\n3,INA219,8\n", "c.csv").size(), 4u);
}

TEST(LongFormLogs, NestedRaplDomainsAreNotSummed) {
    std::string log = "time_s,domain,power_W\n";
    for (int k = 0; k < 4; ++k) log += std::to_string(k) + ",package-0,20\n" + std::to_string(k) + ",core,12\n" + std::to_string(k) + ",dram,4\n";
    const std::string why = error_of(log, "auto", {{"series", "all"}});
    EXPECT_NE(why.find("contain one another"), std::string::npos) << why;
    EXPECT_DOUBLE_EQ(parse_power_log(log, "n.csv", "auto", {{"series", "sum:domain=package-0|dram"}}).w[0], 24);
}

TEST(LongFormLogs, MissingSeriesInAPollIsRefusedInsideAndDroppedAtTheEnds) {
    std::string log = "time_s,gpu,power_W\n0,a,10\n0,b,20\n1,a,11\n1,b,21\n2,a,12\n2,b,22\n3,a,13\n";
    const PowerTrace all = parse_power_log(log, "g.csv", "auto", {{"series", "all"}});
    ASSERT_EQ(all.size(), 3u);  // the last poll lacks b: dropped
    EXPECT_DOUBLE_EQ(all.w[2], 34);
    log = "time_s,gpu,power_W\n0,a,10\n0,b,20\n1,a,11\n2,a,12\n2,b,22\n3,a,13\n3,b,23\n";
    EXPECT_NE(error_of(log, "auto", {{"series", "all"}}).find("x.log:4: this poll holds 1 of the 2 series"), std::string::npos);
}

// Item 1: cumulative energy counters read as differences.
TEST(EnergyCounters, MicrojouleCounterIsReadAsDifferences) {
    // powercap energy_uj: 10 W for 3 s, polled every 0.5 s
    std::string log = "time_s,energy_uj\n";
    for (int k = 0; k <= 6; ++k) log += std::to_string(k * 0.5) + "," + std::to_string(1000000000LL + k * 5000000LL) + "\n";
    const PowerTrace tr = parse_power_log(log, "rapl.csv");
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
    ASSERT_EQ(tr.size(), 6u);
    ASSERT_TRUE(tr.first_interval_start.has_value());
    EXPECT_DOUBLE_EQ(*tr.first_interval_start, 0.0);
    EXPECT_NEAR(tr.w[0], 10, 1e-9);
    EXPECT_NEAR(joules(tr), 30, 1e-9);  // the counter's rise
    EXPECT_TRUE(mentions(tr.notes, "read as differences"));
}

TEST(EnergyCounters, UnitsFromTheNameAndWrapsAtTheStatedRange) {
    // kWh, Wh, mWh and J
    EXPECT_NEAR(joules(parse_power_log("time_s,energy_kWh\n0,1.0\n3600,1.1\n7200,1.2\n", "k.csv")), 0.2 * 3.6e6, 1e-6);
    EXPECT_NEAR(joules(parse_power_log("time_s,Energy (Wh)\n0,2\n36,3\n72,4\n", "w.csv")), 7200, 1e-9);
    EXPECT_NEAR(joules(parse_power_log("time_s,energy_mWh\n0,2\n3.6,3\n7.2,5\n", "m.csv")), 3 * 3.6, 1e-9);  // 1 W, then 2 W
    EXPECT_NEAR(joules(parse_power_log("time_s,pkg_joules\n0,100\n1,112\n2,125\n", "j.csv")), 25, 1e-9);
    // a counter running backwards is refused naming the line and the option
    const std::string back = "time_s,energy_uj\n0,262000000000\n1,262010000000\n2,5000000\n3,15000000\n";
    const std::string why = error_of(back);
    EXPECT_NE(why.find("x.log:4: energy counter 'energy_uj' runs backwards"), std::string::npos) << why;
    EXPECT_NE(why.find("max_energy_range_uj="), std::string::npos) << why;
    // with the range it wraps: 262143328850 uJ is a common max_energy_range_uj
    const PowerTrace w = parse_power_log(back, "r.csv", "auto", {{"max_energy_range_uj", "262143328850"}});
    ASSERT_EQ(w.size(), 3u);
    EXPECT_NEAR(w.w[0], 10, 1e-6);
    EXPECT_NEAR(w.w[1], (262143328850.0 - 262010000000.0 + 5000000) * 1e-6, 1e-6);
    EXPECT_NEAR(w.w[2], 10, 1e-6);
    EXPECT_TRUE(mentions(w.notes, "1 counter wrap(s) unwrapped"));
    // no unit in the name: asked for
    EXPECT_NE(error_of("time_s,energy\n0,1\n1,2\n2,3\n").find("energy_unit="), std::string::npos);
    // a logger with a power column and a cumulative energy column still reads the power
    EXPECT_EQ(parse_power_log("time_s,power_W,cumulative_energy_wh\n0,5,0\n1,5,0.0014\n2,5,0.0028\n", "p.csv").kind, SampleKind::Instant);
}

// Item 4 for counters: the header's unit is evidence, tested against the source like a power unit.
TEST(EnergyCounters, AHeaderUnitThatPutsTheWholeLogBeyondTheSourceIsRefusedNamingBoth) {
    // a meter counting mJ under an energy_uj header: 10 W read as 0.01 W for a computer
    std::string log = "time_s,energy_uj\n";
    for (int k = 0; k <= 6; ++k) log += std::to_string(k * 0.5) + "," + std::to_string(1000000 + k * 5000) + "\n";
    const std::string e = error_of(log);
    EXPECT_NE(e.find("x.log: energy counter 'energy_uj' says uJ, but counted in uJ its rises are 0.01 to 0.01 W, less than"), std::string::npos) << e;
    EXPECT_NE(e.find("(at least 0.5 W); in mJ they would be 10 to 10 W. Pass energy_unit=mJ if it counts mJ, or energy_unit=uJ"),
              std::string::npos) << e;
    // a unit given as an option is the user's word
    EXPECT_NEAR(parse_power_log(log, "x.log", "auto", {{"energy_unit", "uJ"}}).w[0], 0.01, 1e-12);
    EXPECT_NEAR(parse_power_log(log, "x.log", "auto", {{"energy_unit", "mJ"}}).w[0], 10, 1e-9);
    // Wh under a kWh header: 100 W read as 100 kW, above what a computer or server node can draw
    const std::string k = error_of("time_s,energy_kWh\n0,1\n36,2\n72,3\n");
    EXPECT_NE(k.find("says kWh, but counted in kWh its rises are 100000 to 100000 W, more than"), std::string::npos) << k;
    EXPECT_NE(k.find("in Wh they would be 100 to 100 W"), std::string::npos) << k;
}

TEST(EnergyCounters, LongFormCountersPerSeries) {
    // two sockets' package counters in one long log; each series differenced on its own
    std::string log = "time_s,socket,energy_uj\n";
    for (int k = 0; k <= 4; ++k)
        log += std::to_string(k) + ",0," + std::to_string(1000000 + k * 20000000LL) + "\n" + std::to_string(k) + ",1," +
               std::to_string(900000000 + k * 30000000LL) + "\n";
    EXPECT_NE(error_of(log).find("2 series"), std::string::npos);
    const PowerTrace s1 = parse_power_log(log, "l.csv", "auto", {{"series", "socket=1"}});
    EXPECT_NEAR(s1.w[0], 30, 1e-9);
    EXPECT_NEAR(joules(s1), 120, 1e-9);
    const PowerTrace all = parse_power_log(log, "l.csv", "auto", {{"series", "all"}});
    ASSERT_EQ(all.size(), 4u);
    EXPECT_NEAR(all.w[0], 50, 1e-9);
    EXPECT_NEAR(joules(all), 200, 1e-9);  // 4 s x (20 + 30) W, not a sawtooth
}

// Item 3: time stamps. UTC offsets honoured; date --iso-8601=ns (a comma before the fraction).
TEST(TimeStamps, NvidiaSmiOffsetsAreHonoured) {
    const std::string log = "timestamp, power.draw [W]\n2025-09-08T17:26:50+08:00, 40.0 W\n2025-09-08T17:26:51+08:00, 42.0 W\n"
                            "2025-09-08T17:26:52+08:00, 44.0 W\n";
    const PowerTrace tr = parse_power_log(log, "smi.csv", "nvidia-smi");
    EXPECT_FALSE(tr.local_time) << "the stamps carry their zone";
    EXPECT_TRUE(tr.wall_clock);
    EXPECT_DOUBLE_EQ(tr.t[0], 1757323610.0);  // 09:26:50 UTC
    EXPECT_TRUE(mentions(tr.notes, "carry their UTC offset"));
    EXPECT_FALSE(mentions(tr.notes, "no time zone"));
    // a zone given for zoned stamps is refused (it would move them twice)
    EXPECT_NE(error_of(log, "nvidia-smi", {{"utc_offset", "+08:00"}}).find("no local wall-clock"), std::string::npos);
    // zone-less stamps stay local time
    EXPECT_TRUE(parse_power_log("timestamp, power.draw [W]\n2025/09/08 17:26:50.000, 40.0 W\n2025/09/08 17:26:51.000, 41 W\n", "s.csv").local_time);
    // a mix is refused naming the line
    const std::string mixed = "timestamp, power.draw [W]\n2025-09-08T17:26:50+08:00, 40.0 W\n2025/09/08 17:26:51.000, 41 W\n";
    EXPECT_NE(error_of(mixed, "nvidia-smi").find("x.log:3: timestamp '2025/09/08 17:26:51.000' has no time zone"), std::string::npos);
}

// series= is accepted by nvidia-smi logs too, meaning what gpu= means.
TEST(LongFormLogs, NvidiaSmiTakesSeriesLikeGpu) {
    const std::string log = "timestamp, index, power.draw [W]\n2025/09/08 17:26:50.000, 0, 40.0 W\n2025/09/08 17:26:50.010, 1, 60.0 W\n"
                            "2025/09/08 17:26:51.000, 0, 42.0 W\n2025/09/08 17:26:51.010, 1, 62.0 W\n";
    EXPECT_NE(error_of(log).find("2 GPUs in the log"), std::string::npos);
    EXPECT_DOUBLE_EQ(parse_power_log(log, "s.csv", "auto", {{"series", "index=1"}}).w[0], 60.0);
    EXPECT_DOUBLE_EQ(parse_power_log(log, "s.csv", "auto", {{"series", "all"}}).w[1], 104.0);
    EXPECT_NE(error_of(log, "auto", {{"series", "uuid=1"}}).find("told apart by index; pass series=index=VALUE"), std::string::npos);
    EXPECT_NE(error_of(log, "auto", {{"series", "all"}, {"gpu", "0"}}).find("not both"), std::string::npos);
}

TEST(TimeStamps, IsoNanosecondStampsWithACommaBeforeTheFraction) {
    // date --iso-8601=ns: 2025-09-08T17:26:50,250000000+08:00
    const std::string semi = "time;power_W\n2025-09-08T17:26:50,250000000+08:00;5\n2025-09-08T17:26:50,750000000+08:00;7\n"
                             "2025-09-08T17:26:51,250000000+08:00;9\n";
    const PowerTrace a = parse_power_log(semi, "ns.csv");
    EXPECT_NEAR(a.t[0], 1757323610.25, 1e-6);
    EXPECT_NEAR(a.t[1] - a.t[0], 0.5, 1e-6);
    EXPECT_FALSE(a.local_time);
    // zoned and zone-less stamps mixed: refused at the first that differs
    EXPECT_NE(error_of("time;power_W\n2025-09-08T17:26:50+08:00;5\n2025-09-08T17:26:51;7\n2025-09-08T17:26:52+08:00;9\n")
                  .find("x.log:3: time stamp '2025-09-08T17:26:51' has no time zone"),
              std::string::npos);
    // the same under a ',' separator: the stamp's comma does not split the row
    std::string comma = semi;
    for (char& c : comma)
        if (c == ';') c = ',';
    const PowerTrace b = parse_power_log(comma, "ns.csv");
    ASSERT_EQ(b.size(), 3u);
    EXPECT_NEAR(b.t[2] - b.t[0], 1.0, 1e-6);
    EXPECT_DOUBLE_EQ(b.w[2], 9);
}

// Item 3: JSON. Scaphandre's JSON Lines read (microwatts); other JSON refused as JSON.
std::string scaphandre_step(double t, double host_uw, double s0_uw, double dram_uw) {
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "{\"host\":{\"consumption\":%.1f,\"timestamp\":%.3f,\"components\":{\"disks\":null}},\"consumers\":[{\"exe\":\"/usr/bin/x\","
                  "\"pid\":42,\"consumption\":1000.0,\"timestamp\":%.3f}],\"sockets\":[{\"id\":0,\"consumption\":%.1f,\"domains\":[{\"name\":"
                  "\"core\",\"consumption\":1.0,\"timestamp\":%.3f},{\"name\":\"dram\",\"consumption\":%.1f,\"timestamp\":%.3f}],\"timestamp\":%.3f}]}",
                  host_uw, t, t, s0_uw, t, dram_uw, t, t);
    return buf;
}

TEST(JsonLogs, ScaphandreJsonLinesInMicrowatts) {
    std::string log;
    for (int k = 0; k < 4; ++k) log += scaphandre_step(1757323610.0 + 2 * k, 31.5e6 + k * 1e6, 20e6, 3e6) + "\n";
    EXPECT_EQ(detect_power_log_format(log, "s.json"), "scaphandre");
    const PowerTrace host = parse_power_log(log, "s.json");
    ASSERT_EQ(host.size(), 4u);
    EXPECT_DOUBLE_EQ(host.w[0], 31.5);
    EXPECT_TRUE(host.wall_clock);
    EXPECT_EQ(host.kind, SampleKind::IntervalMean);
    EXPECT_DOUBLE_EQ(parse_power_log(log, "s.json", "auto", {{"part", "socket:0"}}).w[1], 20);
    EXPECT_DOUBLE_EQ(parse_power_log(log, "s.json", "auto", {{"part", "socket:0:dram"}}).w[2], 3);
    // one JSON array of the same steps
    std::string arr = "[";
    for (int k = 0; k < 3; ++k) arr += (k ? "," : "") + scaphandre_step(100.0 + k, 10e6, 5e6, 1e6);
    EXPECT_EQ(parse_power_log(arr + "]", "a.json").size(), 3u);
    // a broken line names its line
    EXPECT_NE(error_of(log + "{\"host\": \n").find("x.log:5: not valid JSON"), std::string::npos);
    EXPECT_NE(error_of(log, "auto", {{"part", "gpu"}}).find("expected host, socket:N"), std::string::npos);
}

TEST(JsonLogs, OtherJsonIsRefusedAsJsonNotAsACsv) {
    const std::string why = error_of("{\"t\": 1.0, \"watts\": 5}\n{\"t\": 2.0, \"watts\": 6}\n");
    EXPECT_NE(why.find("x.log:1: a JSON document (JSON Lines"), std::string::npos) << why;
    EXPECT_EQ(why.find("needs a power column"), std::string::npos) << why;
    EXPECT_NE(error_of("[{\"t\": 1.0, \"watts\": 5},\n{\"t\": 2.0, \"watts\": 6}]\n").find("a JSON document"), std::string::npos);
    // a bracketed log line is not JSON
    EXPECT_EQ(error_of("[2024-05-02 10:15:01] 5.1 W\n[2024-05-02 10:15:02] 5.2 W\n").find("JSON"), std::string::npos);
}

// Item 3: commented headers and preambles.
TEST(CsvLayout, CommentedHeaderIsTheHeader) {
    const std::string log = "# logger v2, 10 Hz\n# time_s,bus_V,current_mA\n0.0,5.0,400\n0.1,5.0,420\n0.2,5.0,440\n";
    const PowerTrace tr = parse_power_log(log, "c.csv");
    ASSERT_EQ(tr.size(), 3u);
    EXPECT_DOUBLE_EQ(tr.w[0], 2.0);
    EXPECT_TRUE(mentions(tr.notes, "header read from the comment line 2"));
    // a headerless log without such a comment is still refused as before
    EXPECT_NE(error_of("# logger v2\n0.0,5.0,400\n0.1,5.0,420\n").find("no header row"), std::string::npos);
}

TEST(CsvLayout, PreambleBeforeTheHeaderIsSkipped) {
    // a USB meter export: device, date and settings before the table
    const std::string log = "UM25C USB tester export\nDate: 2025-09-08\nSample interval: 1 s\n\n"
                            "Time(s),Voltage(V),Current(A),Power(W),Joules\n0,5.10,0.50,2.55,0\n1,5.10,0.60,3.06,2.8\n2,5.09,0.70,3.56,6.1\n";
    EXPECT_EQ(detect_power_log_format(log, "um.csv"), "ina219-csv") << "a Joules column is not perf stat";
    const PowerTrace tr = parse_power_log(log, "um.csv");
    ASSERT_EQ(tr.size(), 3u);
    EXPECT_NEAR(tr.w[1], 5.10 * 0.60, 1e-12);
    EXPECT_TRUE(mentions(tr.notes, "skipped the preamble before the header at line 5 (lines 1-4)"));
}

// Item 3: current-only exports (PPK2, Otii, Joulescope): energy needs the supply voltage.
TEST(CurrentOnly, RefusedWithoutVoltageAndReadWithIt) {
    // Nordic PPK2 export: Timestamp(ms),Current(uA),D0-D7
    const std::string ppk2 = "Timestamp(ms),Current(uA),D0-D7\n0.00,1500.0,00000000\n0.01,1520.0,00000000\n0.02,1480.0,00000001\n0.03,1500.0,00000001\n";
    const std::string why = error_of(ppk2);
    EXPECT_NE(why.find("a current-only log (column 'Current(uA)'"), std::string::npos) << why;
    EXPECT_NE(why.find("pass voltage=V"), std::string::npos) << why;
    const PowerTrace tr = parse_power_log(ppk2, "ppk2.csv", "auto", {{"voltage", "3.0"}});
    ASSERT_EQ(tr.size(), 4u);
    EXPECT_NEAR(tr.w[0], 1500e-6 * 3.0, 1e-12);
    EXPECT_NEAR(tr.t[1] - tr.t[0], 1e-5, 1e-12);  // ms
    EXPECT_EQ(tr.quantity, "Current(uA) x voltage=3.0 V");
    // micro sign in the unit
    EXPECT_NEAR(parse_power_log("Time (s),Current (\xc2\xb5" "A)\n0,100\n1,200\n2,300\n", "otii.csv", "auto", {{"voltage", "5"}}).w[1], 1e-3, 1e-12);
    // voltage= on a log that has a voltage is refused
    EXPECT_NE(error_of("time_s,bus_V,current_mA\n0,5,100\n1,5,100\n", "auto", {{"voltage", "5"}}).find("voltage= is for a current-only log"),
              std::string::npos);
}

// Item 3: jetson-stats (jtop) CSV; item 4: which rails a sum covers.
TEST(Jtop, PowerTotByDefaultAndSumsWithoutTheInputRail) {
    const std::string log =
        "time,uptime,CPU1,CPU2,RAM,GPU,Temp CPU,Power VDD_IN,Power VDD_CPU_GPU_CV,Power VDD_SOC,Power TOT,jetson_clocks,nvp model\n"
        "2025-09-08 17:26:50.000000,\"1 day, 2:03:04.5\",12,9,0.31,0,41.2,4810,1201,1603,4810,OFF,15W\n"
        "2025-09-08 17:26:51.000000,\"1 day, 2:03:05.5\",40,35,0.32,80,42.0,7210,3601,1609,7210,OFF,15W\n"
        "2025-09-08 17:26:52.000000,\"1 day, 2:03:06.5\",41,33,0.32,81,42.5,7190,3580,1610,7190,OFF,15W\n";
    EXPECT_EQ(detect_power_log_format(log, "jtop.csv"), "jtop");
    const PowerTrace tot = parse_power_log(log, "jtop.csv");
    ASSERT_EQ(tot.size(), 3u);
    EXPECT_DOUBLE_EQ(tot.w[0], 4.810);
    EXPECT_TRUE(tot.local_time);
    const PowerTrace sum = parse_power_log(log, "jtop.csv", "auto", {{"rail", "sum"}});
    EXPECT_DOUBLE_EQ(sum.w[1], 3.601 + 1.609) << "VDD_IN holds the other rails: left out of the sum";
    EXPECT_NE(sum.quantity.find("input rail VDD_IN left out"), std::string::npos) << sum.quantity;
    EXPECT_DOUBLE_EQ(parse_power_log(log, "jtop.csv", "auto", {{"rail", "VDD_SOC"}}).w[2], 1.610);
    EXPECT_NE(error_of(log, "auto", {{"rail", "VDD_GPU"}}).find("rail 'VDD_GPU' is not in the log"), std::string::npos);
}

TEST(Jtop, TegrastatsRailSumLeavesTheInputRailOut) {
    const std::string log = "RAM 2000/3964MB CPU [5%@102,off,off,3%@102] POM_5V_IN 2793/2793 POM_5V_GPU 76/76 POM_5V_CPU 320/320\n"
                            "RAM 2000/3964MB CPU [5%@102,off,off,3%@102] POM_5V_IN 2893/2843 POM_5V_GPU 86/81 POM_5V_CPU 330/325\n";
    const PowerTrace tr = parse_power_log(log, "t.log", "tegrastats", {{"rail", "sum"}, {"interval_ms", "1000"}});
    EXPECT_NEAR(tr.w[0], 0.076 + 0.320, 1e-12);
    EXPECT_NE(tr.quantity.find("POM_5V_IN left out"), std::string::npos) << tr.quantity;
}

// Item 3: Raspberry Pi 5 PMIC dumps (vcgencmd pmic_read_adc) with a time stamp line before each.
std::string pmic_dump(double core_a, double sys_a) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "     3V3_SYS_A current(1)=%.8fA\n     VDD_CORE_A current(7)=%.8fA\n     HDMI_A current(22)=0.00000000A\n"
                  "     3V3_SYS_V volt(9)=3.31002000V\n     VDD_CORE_V volt(15)=0.80000000V\n     EXT5V_V volt(24)=5.14647000V\n",
                  sys_a, core_a);
    return buf;
}

TEST(PiPmic, DumpsAfterTimeStampsSumIxVOverPairedRails) {
    std::string log;
    for (int k = 0; k < 3; ++k) log += std::to_string(1757323610 + k) + ".250000000\n" + pmic_dump(2.0 + k, 0.1);
    EXPECT_EQ(detect_power_log_format(log, "pmic.log"), "pi5-pmic");
    const PowerTrace tr = parse_power_log(log, "pmic.log");
    ASSERT_EQ(tr.size(), 3u);
    EXPECT_NEAR(tr.w[0], 2.0 * 0.8 + 0.1 * 3.31002, 1e-9);
    EXPECT_NEAR(tr.t[1] - tr.t[0], 1.0, 1e-6);
    EXPECT_TRUE(tr.wall_clock);
    EXPECT_FALSE(tr.local_time);
    EXPECT_TRUE(mentions(tr.notes, "left out, without a partner reading: EXT5V_V, HDMI_A"));
    // date --iso-8601=ns stamps work too
    std::string iso;
    for (int k = 0; k < 2; ++k) iso += "2025-09-08T17:26:5" + std::to_string(k) + ",250000000+08:00\n" + pmic_dump(2.0, 0.1);
    EXPECT_NEAR(parse_power_log(iso, "p.log").t[0], 1757323610.25, 1e-6);
    // without stamps: refused naming the fix, or placed by interval_s
    const std::string bare = pmic_dump(2.0, 0.1) + pmic_dump(2.5, 0.1) + pmic_dump(3.0, 0.1);
    EXPECT_NE(error_of(bare).find("date +%s.%N"), std::string::npos);
    EXPECT_EQ(parse_power_log(bare, "b.log", "auto", {{"interval_s", "1"}}).size(), 3u);
}

// The live PMIC sampler runs vcgencmd at each poll (here a script standing in for it).
TEST(PiPmic, LiveSamplerSumsTheRailsOfEachDump) {
    const auto dir = std::filesystem::temp_directory_path() / ("trn_pmic_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto fake = dir / "vcgencmd";
    {
        std::ofstream f(fake);
        f << "#!/bin/sh\n[ \"$1\" = pmic_read_adc ] || exit 2\nprintf '%s\\n' '" << pmic_dump(2.0, 0.1).substr(5) << "'\n";
    }
    std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
    SamplerOptions so;
    so.vcgencmd = fake.string();
    const auto s = make_power_sampler("pmic:vcgencmd", so);
    s->poll(1.0);
    s->poll(2.0);
    const PowerTrace tr = s->trace();
    ASSERT_EQ(tr.size(), 2u);
    EXPECT_NEAR(tr.w[1], 2.0 * 0.8 + 0.1 * 3.31002, 1e-9);
    EXPECT_TRUE(mentions(tr.notes, "left out, without a partner reading: EXT5V_V, HDMI_A"));
    // a missing program and a relative path are errors naming them
    so.vcgencmd = (dir / "missing").string();
    EXPECT_THROW(make_power_sampler("pmic", so)->poll(1.0), trn::Error);
    so.vcgencmd = "vcgencmd";
    try {
        make_power_sampler("pmic", so)->poll(1.0);
        ADD_FAILURE() << "a relative program path was run";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("absolute path"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

// The fuzz seeds written for this round read as the tests above say.
TEST(Round3Seeds, ExamplesInTheFuzzCorpusRead) {
    auto example = [](const std::string& file) {
        const std::string path = std::string(TRN_POWER_LOG_EXAMPLES) + "/" + file;
        return path;
    };
    const RunSummaries cc = read_run_summaries(example("codecarbon_emissions.csv"));
    EXPECT_EQ(cc.runs.size(), 3u);
    EXPECT_EQ(cc.machines.size(), 2u);
    EXPECT_NE(cc.machines[1].find("gpu_model=1 x NVIDIA A100-SXM4-40GB"), std::string::npos) << cc.machines[1];
    EXPECT_NEAR(joules(read_power_log(example("scaphandre.jsonl"))), 2 * (32.5 + 33.5 + 34.5), 1e-9);
    const PowerTrace rapl = read_power_log(example("rapl_long_form_energy_uj.csv"), "auto", {{"series", "all"}});
    EXPECT_NEAR(joules(rapl), (25 + 4 + 30 + 4) * 2.5, 1e-6);
    EXPECT_NEAR(joules(read_power_log(example("rapl_long_form_energy_uj.csv"), "auto", {{"series", "socket=1,domain=package-1"}})), 30 * 2.5, 1e-6);
}

}  // namespace
}  // namespace trn::energy
