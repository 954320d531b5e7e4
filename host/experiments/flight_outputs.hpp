#pragma once
// Reading the outputs of flight jobs ({"params": {preset, conversion, map_age, run}, "result": {...}})
// for the conversion, robustness and odometry tables, and the claims computed from them.
#include <climits>
#include <string>
#include <utility>
#include <vector>

#include "study.hpp"
#include "table.hpp"
#include "trn/localize/localization.hpp"

namespace trn::experiments {

// A number from a job's result; NaN where the job stored null (a non-finite value). Results written
// before the slopes took summary.json's names (filter_slope_m_per_km, odometry_slope_m_per_km) are
// read under the new names too.
double get(const Json& result, const char* key);

// A flight job's result numbers under the names summary.json uses (localize/report.hpp), plus
// steps, distance, mean particles and the lock monitor's counters; a study adds its own.
Json flight_result(const localize::LocalizationSummary& summary);

// The store's names of the error slopes over time broken at 35 s (localize::kErrorSlopeBreakS; m/s),
// and the summary's values under them. Results stored before these were added lack them.
inline constexpr const char* kFilterSlopeBefore = "filter_error_slope_before_35s_m_per_s";
inline constexpr const char* kFilterSlopeAfter = "filter_error_slope_after_35s_m_per_s";
inline constexpr const char* kOdometrySlopeBefore = "odometry_error_slope_before_35s_m_per_s";
inline constexpr const char* kOdometrySlopeAfter = "odometry_error_slope_after_35s_m_per_s";
std::vector<std::pair<std::string, double>> break_slopes(const localize::LocalizationSummary& summary);

// Which jobs a mean is taken over: "" matches any preset / conversion; map ages in [min_age, max_age]
// (a job without map_age, e.g. odometry's, counts as age 0).
struct FlightCell {
    std::string preset, conversion;
    int min_age = 0, max_age = INT_MAX;
};
inline FlightCell at_age(std::string preset, std::string conversion, int age) { return {std::move(preset), std::move(conversion), age, age}; }
// The finite values of `key` over the matching jobs, in job order.
std::vector<double> values_of(const std::vector<Json>& outputs, const char* key, const FlightCell& cell);
// Mean of `key` over the matching jobs with a finite value; NaN when none.
double mean_of(const std::vector<Json>& outputs, const char* key, const FlightCell& cell);
// The q-quantile (0..1) of the finite values, linear between order statistics (R's type 7, NumPy's
// default); NaN when none; trn::Error for q outside 0..1. quantile(v, 0.5) is the median.
double quantile(std::vector<double> values, double q);

// The paper's "logistic beats linear in 10 of 12 scenarios": in how many of `presets` the mean
// error of `better` is below that of `than` (presets lacking either are not counted).
struct WinCount {
    int wins = 0, scenarios = 0;
};
WinCount scenarios_where_more_accurate(const std::vector<Json>& outputs, const std::vector<std::string>& presets, const std::string& better,
                                       const std::string& than);

// The abstract's "~30 % precision loss on out-of-date maps": how much larger the mean error is on
// maps of another year than on the map of the flight's own year (map age 0), in percent:
// 100 * (mean over jobs with map age > 0 / mean over jobs with map age 0 - 1). `conversion` ""
// pools every function. NaN when either side has no job.
double out_of_date_loss_percent(const std::vector<Json>& outputs, const std::string& conversion);

// How a function's flights spread, one row per function: flights, median, mean and 90th percentile
// of the flights' mean errors, and the share of flights whose mean error exceeds 50 m and 100 m. A
// mean over flights (every table of the dissertation) is ruled by its few lost flights; this shows
// how many there are and what a typical flight does. Not in the dissertation, which prints means only.
Table error_spread(const std::vector<Json>& outputs, const std::vector<std::string>& conversions);

// The filter against the odometry over a study's flights, one row: in how many flights the filter's
// final and mean errors are below the odometry's, the median errors of both, and how many flights
// end within 10 m. `study` names the row.
Table odometry_summary(const std::vector<Json>& outputs, const std::string& study);

// Fig 3.9's trend lines broken at 35 s, over a study's flights, one row: how many flights store the
// fit (results from before it have none and are left out), the median slope of the filter's and
// the odometry's error over time before and after 35 s, in how many flights the filter's error
// grows more slowly than the odometry's after the break and in how many it still falls (still
// converging), the ratio of the median slopes after it (odometry / filter; the dissertation's 11x;
// n/a unless both are positive) and the median of the per-flight ratios over the flights whose
// filter error rises after the break (a falling one has no meaningful ratio).
Table odometry_break_summary(const std::vector<Json>& outputs, const std::string& study);

}  // namespace trn::experiments
