// Issue 46: energy logs, third round. Each silent misread or misleading refusal found on the second
// set of real logs is reproduced here on a small log written for the test.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_summaries.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::string error_of(const std::string& text, const std::string& format = "auto", const ParseOptions& o = {}) {
    try {
        parse_power_log(text, "x.log", format, o);
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

bool mentions(const std::vector<std::string>& list, const std::string& part) {
    for (const auto& s : list)
        if (s.find(part) != std::string::npos) return true;
    return false;
}

double joules(const PowerTrace& tr) {
    return integrate_interval(tr, tr.first_interval_start.value_or(tr.t.front()), tr.t.back()).energy_j;
}

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

}  // namespace
}  // namespace trn::energy
