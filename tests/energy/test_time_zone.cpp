// Logs stamped in local time (issue 16): fixed UTC offsets and tz database zones, and a log one
// hour ahead of its CLOCK_REALTIME markers, which matched no frame without a word and is now
// refused with the offset that would fit (library and a real `trnkit energy integrate`).
#include <gtest/gtest.h>

#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>

#include "../cli/cli_process.hpp"
#include "synthetic_run.hpp"
#include "text_input.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/energy/time_zone.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

double utc(int y, int mo, int d, int h, int mi, double s) { return text::civil_to_unix(y, mo, d, h, mi, s); }

TEST(TimeZone, FixedOffsets) {
    EXPECT_DOUBLE_EQ(TimeZone::fixed("+01:00").local_to_utc(utc(2026, 7, 1, 12, 0, 0)), utc(2026, 7, 1, 11, 0, 0));
    EXPECT_DOUBLE_EQ(TimeZone::fixed("-0530").local_to_utc(utc(2026, 7, 1, 12, 0, 0)), utc(2026, 7, 1, 17, 30, 0));
    EXPECT_DOUBLE_EQ(TimeZone::fixed("+3").offset_at_utc(0), 3 * 3600.0);
    EXPECT_DOUBLE_EQ(TimeZone::fixed("UTC").offset_at_utc(0), 0.0);
    for (const char* bad : {"1", "+25:00", "+01:61", "+1:2:3", "CET", "+"}) EXPECT_THROW(TimeZone::fixed(bad), trn::Error) << bad;
}

TEST(TimeZone, NamedZonesFollowDaylightSaving) {
    if (!fs::exists("/usr/share/zoneinfo/Europe/Vilnius")) GTEST_SKIP() << "tzdata not installed: named zones not checked";
    const TimeZone v = TimeZone::named("Europe/Vilnius");
    EXPECT_DOUBLE_EQ(v.local_to_utc(utc(2026, 1, 15, 12, 0, 0)), utc(2026, 1, 15, 10, 0, 0));  // EET, +2
    EXPECT_DOUBLE_EQ(v.local_to_utc(utc(2026, 7, 1, 12, 0, 0)), utc(2026, 7, 1, 9, 0, 0));     // EEST, +3
    // 2026-10-25 03:30 happens twice (clocks go back at 04:00 EEST): the earlier one, flagged.
    bool ambiguous = false;
    EXPECT_DOUBLE_EQ(v.local_to_utc(utc(2026, 10, 25, 3, 30, 0), &ambiguous), utc(2026, 10, 25, 0, 30, 0));
    EXPECT_TRUE(ambiguous);
    v.local_to_utc(utc(2026, 10, 25, 5, 0, 0), &ambiguous);
    EXPECT_FALSE(ambiguous);
    EXPECT_DOUBLE_EQ(TimeZone::named("America/New_York").local_to_utc(utc(2026, 7, 1, 12, 0, 0)), utc(2026, 7, 1, 16, 0, 0));
    for (const char* bad : {"../etc/passwd", "/etc/localtime", "Europe/Nowhere", "Europe//Vilnius", ""}) EXPECT_THROW(TimeZone::named(bad), trn::Error) << bad;
}

TEST(TimeZone, OptionsConvertOnlyLocalStamps) {
    const std::string log = "timestamp, power.draw [W]\n2026/07/01 12:00:00.000, 20.0 W\n2026/07/01 12:00:00.500, 21.0 W\n";
    const PowerTrace raw = parse_power_log(log, "n.csv");
    EXPECT_TRUE(raw.local_time);
    const PowerTrace moved = parse_power_log(log, "n.csv", "auto", {{"utc_offset", "+03:00"}});
    EXPECT_FALSE(moved.local_time);
    EXPECT_DOUBLE_EQ(moved.t[0], raw.t[0] - 3 * 3600);
    bool noted = false;
    for (const auto& n : moved.notes) noted = noted || n.find("converted to UTC with zone UTC+03:00") != std::string::npos;
    EXPECT_TRUE(noted);
    EXPECT_THROW(parse_power_log(log, "n.csv", "auto", {{"utc_offset", "+03:00"}, {"timezone", "Europe/Vilnius"}}), trn::Error);
    // A log whose stamps are UNIX time (or relative) is not shifted by a zone: refused.
    try {
        parse_power_log("time_s,power_mW\n1764590400.0,2000\n1764590400.1,2100\n", "e.csv", "auto", {{"utc_offset", "+01:00"}});
        FAIL() << "zone applied to UNIX time";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("e.csv: timezone/utc_offset given, but this ina219-csv log has no local"), std::string::npos) << e.what();
    }
}

// A run whose log (nvidia-smi style: local wall clock, no zone) is stamped one hour ahead of UTC.
struct LocalRun {
    test::Timeline tl = test::make_timeline(6, 0.05, 0.05);
    PowerTrace trace;
    LocalRun() {
        const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
        trace = test::sample_trace(tl.markers, test::TraceClock{3600, 0, ref}, ref + 3600 - 0.2, ref + 3600 + 2, 5e-3, 20.0, 30.0, 0, true);
        trace.local_time = true, trace.format = "nvidia-smi";
    }
};

TEST(TimeZone, LogOneHourAheadIsDetectedNotSilentlyEmpty) {
    LocalRun run;
    try {
        integrate_run(run.trace, run.tl.markers, IntegrateRequest{});
        FAIL() << "a log one hour ahead gave a report";
    } catch (const trn::Error& e) {
        const std::string why = e.what();
        EXPECT_NE(why.find("none of the frames lies inside the log"), std::string::npos) << why;
        EXPECT_NE(why.find("read 1 h 00 min earlier"), std::string::npos) << why;
        EXPECT_NE(why.find("pass `utc_offset` +01:00"), std::string::npos) << why;  // the CLI says --utc-offset
    }
    apply_time_zone(run.trace, TimeZone::fixed("+01:00"));
    const RunReport r = integrate_run(run.trace, run.tl.markers, IntegrateRequest{});
    ASSERT_EQ(r.frames.size(), 6u);
    for (const auto& f : r.frames) {
        EXPECT_TRUE(f.energy.flag.empty()) << f.energy.flag;
        EXPECT_NEAR(f.energy.gross_j, 50.0 * f.energy.duration(), f.energy.error_j + 1e-9);
    }
}

std::string nvidia_smi_line(double t, double w) {
    const std::time_t whole = static_cast<std::time_t>(std::floor(t));
    std::tm tm{};
    gmtime_r(&whole, &tm);
    char buf[80];
    std::snprintf(buf, sizeof buf, "%04d/%02d/%02d %02d:%02d:%02d.%03d, %.2f W\n", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min,
                  tm.tm_sec, static_cast<int>(std::lround((t - std::floor(t)) * 1000)) % 1000, w);
    return buf;
}

TEST(TimeZone, CliRefusesLocalLogAndAcceptsUtcOffset) {
    LocalRun run;
    const fs::path dir = fs::temp_directory_path() / ("trn_tz_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string log = (dir / "gpu.csv").string(), markers = (dir / "markers.csv").string(), json = (dir / "run.json").string();
    {
        std::ofstream out(log);
        out << "timestamp, power.draw [W]\n";
        for (std::size_t i = 0; i < run.trace.size(); ++i) out << nvidia_smi_line(run.trace.t[i], run.trace.w[i]);
        std::ofstream(markers) << format_markers(run.tl.markers);
    }
    const auto refused = trn::test::run_trnkit("energy integrate " + log + " --markers " + markers + " --json " + json);
    EXPECT_EQ(refused.code, 1) << refused.output;
    EXPECT_NE(refused.output.find("pass --utc-offset +01:00"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(json));
    const auto ok = trn::test::run_trnkit("energy integrate " + log + " --markers " + markers + " --utc-offset +01:00 --json " + json);
    EXPECT_EQ(ok.code, 0) << ok.output;
    EXPECT_NE(ok.output.find("6 frame(s), 6 usable"), std::string::npos) << ok.output;
    std::ifstream in(json);
    const std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(report.find("\"utc_offset\": \"+01:00\""), std::string::npos) << "the zone is part of the provenance";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace trn::energy
