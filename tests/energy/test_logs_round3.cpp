// Issue 46: energy logs, third round. Each silent misread or misleading refusal found on the second
// set of real logs is reproduced here on a small log written for the test.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
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

}  // namespace
}  // namespace trn::energy
