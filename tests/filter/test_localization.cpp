// Summary statistics and the files a run writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "trn/localize/localization.hpp"
#include "trn/localize/report.hpp"

namespace trn::localize {
namespace {

using filter::FilterCounters;

TEST(Localization, FittedSlopeIsExactOnALine) {
    EXPECT_NEAR(fitted_slope({0, 1, 2, 3}, {1, 3, 5, 7}), 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(fitted_slope({1}, {2})));
    EXPECT_TRUE(std::isnan(fitted_slope({1, 1}, {2, 3})));
}

// Two lines with a kink at 35 s, sampled at 2 Hz from t = 10 s (the first step's time is the
// flight's zero): 40 - 0.5 t before 35 s, 22.5 + 0.1 (t - 35) from it on. Each side's fit must give
// its own slope exactly, the point at the break belonging to the second.
TEST(Localization, BrokenLineFitsEachSideOfTheBreak) {
    std::vector<double> t, y;
    for (int i = 0; i <= 200; ++i) {
        t.push_back(0.5 * i);
        y.push_back(t.back() < 35 ? 40 - 0.5 * t.back() : 22.5 + 0.1 * (t.back() - 35));
    }
    const BrokenLine b = fit_broken_line(t, y, 35);
    EXPECT_NEAR(b.before.slope, -0.5, 1e-12);
    EXPECT_NEAR(b.before.intercept, 40, 1e-10);
    EXPECT_NEAR(b.after.slope, 0.1, 1e-12);
    EXPECT_NEAR(b.after.intercept, 22.5 - 3.5, 1e-10);
    // One whole line over both sides would mix them: its slope is neither.
    const double whole = fitted_slope(t, y);
    EXPECT_GT(std::abs(whole - 0.1), 0.05);
    EXPECT_GT(std::abs(whole + 0.5), 0.05);
    // A side with fewer than two points has no line.
    const BrokenLine none_before = fit_broken_line({35, 36, 37}, {1, 2, 3}, 35);
    EXPECT_TRUE(std::isnan(none_before.before.slope));
    EXPECT_NEAR(none_before.after.slope, 1, 1e-12);
    EXPECT_TRUE(std::isnan(fit_broken_line({1, 2}, {1}, 35).after.slope));  // sizes differ
}

// The summary's broken slopes: error over seconds since the first step, broken at kErrorSlopeBreakS.
TEST(Localization, SummaryBreaksTheErrorLinesAt35Seconds) {
    std::vector<LocalizationRow> rows;
    for (int i = 0; i <= 160; ++i) {  // 80 s at 2 Hz, the clock starting at 100 s
        LocalizationRow r;
        const double t = 0.5 * i;
        r.time_s = 100 + t;
        r.distance_m = 10 * t;
        r.error_m = t < kErrorSlopeBreakS ? 50 - t : 15 + 0.02 * (t - kErrorSlopeBreakS);
        r.odometry_error_m = t < kErrorSlopeBreakS ? 0.2 * t : 7 + 0.3 * (t - kErrorSlopeBreakS);
        rows.push_back(r);
    }
    const LocalizationSummary s = summarise(rows, {}, 1.0);
    EXPECT_NEAR(s.filter_slope_before_break_m_per_s, -1, 1e-9);
    EXPECT_NEAR(s.filter_slope_after_break_m_per_s, 0.02, 1e-9);
    EXPECT_NEAR(s.odometry_slope_before_break_m_per_s, 0.2, 1e-9);
    EXPECT_NEAR(s.odometry_slope_after_break_m_per_s, 0.3, 1e-9);
    // A flight shorter than the break has no second line.
    rows.resize(60);
    EXPECT_TRUE(std::isnan(summarise(rows, {}, 1.0).filter_slope_after_break_m_per_s));
}

std::vector<LocalizationRow> synthetic_rows() {
    std::vector<LocalizationRow> rows(5);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        rows[i].distance_m = 250.0 * i;
        rows[i].error_m = 2.0;
        rows[i].odometry_error_m = 10.0 * i;  // 40 m/km
        rows[i].particles = 100 + 100 * i;
    }
    return rows;
}

TEST(Localization, SummaryUsesTheRowsAsDefined) {
    FilterCounters c;
    c.reinitialisations = 2;
    const LocalizationSummary s = summarise(synthetic_rows(), c, 0.5);
    EXPECT_DOUBLE_EQ(s.filter_mean_error_m, 2.0);
    EXPECT_DOUBLE_EQ(s.odometry_mean_error_m, 20.0);
    EXPECT_DOUBLE_EQ(s.odometry_final_error_m, 40.0);
    EXPECT_NEAR(s.odometry_error_slope_m_per_km, 40.0, 1e-9);
    EXPECT_NEAR(s.filter_error_slope_m_per_km, 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(s.mean_particles, 300.0);
    EXPECT_DOUBLE_EQ(s.frames_per_second, 10.0);
    EXPECT_EQ(s.counters.reinitialisations, 2u);
}

TEST(Localization, SummaryJsonHasTheIssueKeys) {
    const std::string dir = (std::filesystem::temp_directory_path() / "trn_filter_json_test").string();
    std::filesystem::create_directories(dir);
    const LocalizationSummary s = summarise(synthetic_rows(), {}, 1.0);
    write_summary_json(dir + "/summary.json", s, {{"backend", "cpu"}}, {{"seed", 4}});
    std::ifstream in(dir + "/summary.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const char* key : {"filter_mean_error_m", "odometry_mean_error_m", "filter_final_error_m", "odometry_final_error_m",
                            "filter_error_slope_m_per_km", "odometry_error_slope_m_per_km", "mean_particles", "frames_per_second",
                            "backend", "seed"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["backend"], "cpu");
    EXPECT_EQ(j["seed"], 4);
    write_rows_csv(dir + "/rows.csv", synthetic_rows());
    std::ifstream csv(dir + "/rows.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_NE(header.find("error_m"), std::string::npos);
    std::filesystem::remove_all(dir);
}

// Splits one CSV line (no quoting in this file: every cell is a number, a flag or one word).
std::vector<std::string> cells(const std::string& line) {
    std::vector<std::string> out(1);
    for (char ch : line) {
        if (ch == ',')
            out.emplace_back();
        else
            out.back().push_back(ch);
    }
    return out;
}

TEST(Localization, RowsCsvHasTheLockMonitorsColumns) {
    std::vector<LocalizationRow> rows = synthetic_rows();
    rows[0].lock = {};  // not assessed (monitor off or no frame)
    rows[1].lock.contrast = 7.5, rows[1].lock.drift_m = 12, rows[1].lock.drift_bound_m = 90, rows[1].lock.confident = true;
    rows[2].lock.contrast = 1.5, rows[2].lock.drift_m = 20, rows[2].lock.drift_bound_m = 95, rows[2].lock.weak = true;
    rows[3].lock.contrast = 2.0, rows[3].lock.drift_m = 130, rows[3].lock.drift_bound_m = 100, rows[3].lock.weak = true;
    rows[3].lock.inconsistent = true, rows[3].lock.lost = true, rows[3].lock.widen_radius_m = 100;
    rows[4].lock.contrast = 4.0, rows[4].lock.drift_m = 30, rows[4].lock.drift_bound_m = 104, rows[4].lock.inconsistent = true;
    const std::string dir = (std::filesystem::temp_directory_path() / "trn_filter_lock_csv_test").string();
    std::filesystem::create_directories(dir);
    write_rows_csv(dir + "/rows.csv", rows);
    std::ifstream csv(dir + "/rows.csv");
    std::string line;
    std::getline(csv, line);
    const std::vector<std::string> header = cells(line);
    auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        EXPECT_NE(it, header.end()) << name << " missing from " << line;
        return static_cast<std::size_t>(it - header.begin());
    };
    const std::size_t state = column("lock_state"), contrast = column("lock_contrast"), drift = column("lock_drift_m"),
                      bound = column("lock_drift_bound_m"), events = column("lock_lost_events"), radius = column("lock_widen_radius_m");
    ASSERT_FALSE(HasFailure()) << "a lock column is missing";
    std::vector<std::vector<std::string>> table;
    while (std::getline(csv, line)) table.push_back(cells(line));
    std::filesystem::remove_all(dir);
    ASSERT_EQ(table.size(), rows.size());
    for (const auto& row : table) ASSERT_EQ(row.size(), header.size());
    const std::vector<std::string> states{"none", "fix", "weak", "lost", "inconsistent"};
    const std::vector<std::string> counts{"0", "0", "0", "1", "1"}, radii{"0", "0", "0", "100", "0"};
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(table[i][state], states[i]) << "row " << i;
        EXPECT_EQ(table[i][events], counts[i]) << "row " << i;
        EXPECT_EQ(table[i][radius], radii[i]) << "row " << i;
    }
    EXPECT_EQ(table[0][contrast], "") << "unknown evidence is an empty cell, never nan";
    EXPECT_EQ(table[0][drift], "");
    EXPECT_EQ(table[1][contrast], "7.5");
    EXPECT_EQ(table[3][drift], "130");
    EXPECT_EQ(table[3][bound], "100");
}

}  // namespace
}  // namespace trn::localize
