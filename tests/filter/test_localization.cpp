// Summary statistics and the files a run writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "trn/filter/localization.hpp"
#include "trn/filter/report.hpp"

namespace trn::filter {
namespace {

TEST(Localization, FittedSlopeIsExactOnALine) {
    EXPECT_NEAR(fitted_slope({0, 1, 2, 3}, {1, 3, 5, 7}), 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(fitted_slope({1}, {2})));
    EXPECT_TRUE(std::isnan(fitted_slope({1, 1}, {2, 3})));
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

}  // namespace
}  // namespace trn::filter
