// Every numeric parser option has a stated range (energy/src/core/option_ranges.hpp, issue 45
// class 6 / 46): `period_s=1e308` and `1e-300` were taken as they came. A value outside is
// refused naming the option, the value and the range; values inside read as before.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "../cli/cli_process.hpp"
#include "option_ranges.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::string refusal(const std::string& log, const std::string& format, const ParseOptions& options) {
    try {
        parse_power_log(log, "x.log", format, options);
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

const std::string kIndexed = "index,power_W\n0,1.5\n1,1.6\n2,1.7\n";  // a row index: needs period_s

TEST(OptionRanges, PeriodOutsideItsRangeIsRefusedNamingTheOption) {
    EXPECT_NE(refusal(kIndexed, "ina219-csv", {{"period_s", "1e308"}}).find("option period_s=1e308 is outside 1e-06..3600 s"), std::string::npos)
        << refusal(kIndexed, "ina219-csv", {{"period_s", "1e308"}});
    EXPECT_NE(refusal(kIndexed, "ina219-csv", {{"period_s", "1e-300"}}).find("option period_s=1e-300 is outside 1e-06..3600 s"), std::string::npos);
    EXPECT_NE(refusal(kIndexed, "auto", {{"period_s", "-1"}}).find("option period_s=-1 is outside"), std::string::npos);
    // Inside the range, as before.
    const PowerTrace t = parse_power_log(kIndexed, "x.log", "ina219-csv", {{"period_s", "0.5"}});
    ASSERT_EQ(t.t.size(), 3u);
    EXPECT_DOUBLE_EQ(t.t[2] - t.t[0], 1.0);
}

TEST(OptionRanges, EveryOtherNumericOptionIsBoundedToo) {
    const std::string nvsmi = "index, power.draw [W]\n0, 50.0\n0, 51.0\n0, 52.0\n";
    EXPECT_NE(refusal(nvsmi, "nvidia-smi", {{"interval_ms", "1e300"}}).find("option interval_ms=1e300 is outside 0.001..3.6e+06 ms"),
              std::string::npos)
        << refusal(nvsmi, "nvidia-smi", {{"interval_ms", "1e300"}});
    EXPECT_NE(refusal(kIndexed, "ina219-csv", {{"period_s", "1"}, {"max_power_w", "1e300"}}).find("option max_power_w=1e300 is outside"),
              std::string::npos);
    const std::string ticks = "(1, 5.0, 100, 500)\n(2, 5.0, 100, 500)\n(3, 5.0, 100, 500)\n";
    EXPECT_NE(refusal(ticks, "ina219-tuples", {{"tick_period_s", "1e-300"}}).find("option tick_period_s=1e-300 is outside"), std::string::npos);
    EXPECT_NE(refusal(ticks, "ina219-tuples", {{"max_bus_v", "1e308"}}).find("option max_bus_v=1e308 is outside"), std::string::npos);
    const std::string raw = "time_s,shunt,bus\n0,100,1000\n1,100,1000\n2,100,1000\n";
    EXPECT_NE(refusal(raw, "ina219-raw", {{"shunt_ohm", "1e-300"}}).find("option shunt_ohm=1e-300 is outside"), std::string::npos);
    EXPECT_NE(refusal(raw, "ina219-raw", {{"current_lsb", "1e300"}}).find("option current_lsb=1e300 is outside"), std::string::npos);
    const std::string current = "Timestamp(ms),Current(uA)\n0,100\n1,110\n2,120\n";
    EXPECT_NE(refusal(current, "ina219-csv", {{"voltage", "1e-300"}}).find("option voltage=1e-300 is outside"), std::string::npos);
    const std::string counter = "time_s,energy_uj\n0,1000\n1,2001000\n2,4001000\n";
    EXPECT_NE(refusal(counter, "ina219-csv", {{"max_energy_range_uj", "1e300"}}).find("option max_energy_range_uj=1e300 is outside"),
              std::string::npos);
}

TEST(OptionRanges, EveryRangeIsAProperInterval) {
    for (const OptionRange& r : kOptionRanges) {
        EXPECT_GT(r.max, r.min) << r.key;
        EXPECT_GE(r.min, 0) << r.key;
        EXPECT_EQ(option_range(r.key), &r) << r.key << " listed twice";
    }
    EXPECT_EQ(option_range("no_such_option"), nullptr);
}

// The CLI names the option too, one line, exit 1, before anything is written.
TEST(OptionRanges, TheCliRefusesNamingTheOption) {
    const std::string log = testing::TempDir() + "/option_ranges_" + std::to_string(::getpid()) + ".csv";
    { std::ofstream(log) << kIndexed; }
    const auto r = test::run_trnkit("energy inspect " + log + " --format ina219-csv --opt period_s=1e308");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("option period_s=1e308 is outside 1e-06..3600 s"), std::string::npos) << r.output;
    std::remove(log.c_str());
}

}  // namespace
}  // namespace trn::energy
