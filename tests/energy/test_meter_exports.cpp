// The bench meters docs/ENERGY.md's format table names beside the loggers (issue 46 item 3 / the
// table's rows for Nordic PPK2, Otii, Joulescope and USB meters): each export shape is read by the
// generic CSV reader (ina219-csv) or refused naming the option it needs. The USB meter headers are
// the ones a public TC66C logger writes (TheHWcave/TC66, TC66C.py: `Time[S],Volt[V],Current[A],
// Power[W]`, with --all the charge/energy groups and D+/D-; recordings read back as `Rec,...`);
// the Otii and Joulescope headers are our reading of their CSV exports, not checked against a
// real file (none is in the shared logs). Sample values are made up.
#include <gtest/gtest.h>

#include <string>

#include "log_checks.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

using test::error_of;
using test::mentions;

TEST(MeterExports, Tc66cLoggerCsvIsReadAsVoltsTimesAmps) {
    const std::string tc66 = "Time[S],Volt[V],Current[A],Power[W]\n  0.0,05.1020,0.50210,02.5617\n  1.0,05.1010,0.61230,03.1233\n"
                             "  2.0,05.0990,0.70110,03.5749\n";
    EXPECT_EQ(detect_power_log_format(tc66, "tc66.csv"), "ina219-csv");
    const PowerTrace t = parse_power_log(tc66, "tc66.csv");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(t.w[1], 5.1010 * 0.61230, 1e-12);
    EXPECT_DOUBLE_EQ(t.t[2] - t.t[0], 2.0);
    // --all: charge and energy groups, temperature and the data lines (a USB device: cap 240 W)
    const std::string all = "Time[S],Volt[V],Current[A],Power[W],Res[Ohm],G0[mAh],G0[mWh],G1[mAh],G1[mWh],Temp[C],D+[V],D-[V]\n"
                            "  0.0,05.1020,0.50210,02.5617,10.2,12,61,0,0,31,0.60,0.60\n  1.0,05.1010,0.61230,03.1233,8.3,12,62,0,0,31,0.60,0.60\n";
    const PowerTrace a = parse_power_log(all, "tc66all.csv");
    ASSERT_EQ(a.size(), 2u);
    EXPECT_NEAR(a.w[0], 5.1020 * 0.50210, 1e-12);
    EXPECT_TRUE(mentions(a.notes, "a USB-powered device")) << "source usb from the D+/D- columns";
}

TEST(MeterExports, Tc66cRecordingsNeedTheirIntervalAsARowIndex) {
    // The meter's own recordings, read back: a record number, no time.
    const std::string rec = "Rec,Volt[V],Current[A]\n   1,05.1020,0.50210\n   2,05.1010,0.61230\n   3,05.0990,0.70110\n";
    EXPECT_NE(error_of(rec).find("no time column among 'Rec,Volt[V],Current[A]'; pass time=NAME"), std::string::npos) << error_of(rec);
    const PowerTrace t = parse_power_log(rec, "rec.csv", "auto", {{"time", "Rec"}, {"time_unit", "index"}, {"period_s", "1"}});
    ASSERT_EQ(t.size(), 3u);
    EXPECT_DOUBLE_EQ(t.t[2] - t.t[0], 2.0);
    EXPECT_NEAR(t.w[2], 5.0990 * 0.70110, 1e-12);
}

TEST(MeterExports, JoulescopeCsvNeedsItsUnitsNamed) {
    // Columns without units: refused until the current's unit is given; current-only, also voltage=.
    const std::string js = "#time,current,voltage,power\n0.0,0.1,3.3,0.33\n0.001,0.12,3.3,0.396\n0.002,0.11,3.3,0.363\n";
    EXPECT_NE(error_of(js).find("current column 'current' has no unit in its name (A? mA? uA?); pass current_unit=A, mA or uA"),
              std::string::npos)
        << error_of(js);
    const PowerTrace t = parse_power_log(js, "js.csv", "auto", {{"current_unit", "A"}});
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(t.w[1], 3.3 * 0.12, 1e-12);
    const std::string current = "#time,current\n0.0,0.1\n0.001,0.12\n0.002,0.11\n";
    EXPECT_NE(error_of(current).find("energy needs the supply voltage; pass voltage=V"), std::string::npos) << error_of(current);
    EXPECT_NEAR(parse_power_log(current, "jsi.csv", "auto", {{"voltage", "3.3"}, {"current_unit", "A"}}).w[1], 3.3 * 0.12, 1e-12);
}

TEST(MeterExports, OtiiCurrentExportNeedsTheSupplyVoltage) {
    const std::string otii = "Timestamp (s),Main current (A)\n0,0.010\n0.001,0.012\n0.002,0.011\n";
    EXPECT_NE(error_of(otii).find("a current-only log (column 'Main current (A)'"), std::string::npos) << error_of(otii);
    const PowerTrace t = parse_power_log(otii, "otii.csv", "auto", {{"voltage", "3.3"}});
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(t.w[1], 3.3 * 0.012, 1e-12);
    EXPECT_EQ(t.quantity, "Main current (A) x voltage=3.3 V");
}

}  // namespace
}  // namespace trn::energy
