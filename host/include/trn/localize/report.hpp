#pragma once
// A localization run on disk: per-step CSV, summary JSON and gnuplot plots (trajectories on the
// map as the dissertation's Fig. 3.10, error over distance with trend lines as its Fig. 3.9).
#include <map>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "trn/localize/localization.hpp"
#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// One line per filter step. The lock monitor's columns: lock_state (none = not assessed: monitor
// off or no frame; else the strongest of lost > fix > inconsistent > weak > unknown > ok; localizer.hpp
// says what each needs), lock_contrast,
// lock_drift_m and lock_drift_bound_m (empty when unknown), lock_lost_events (running count) and
// lock_widen_radius_m (the widened search's radius on a lost step, else 0).
// `heading_columns` (compass-less runs) appends truth_yaw_deg, estimate_yaw_deg, estimate_yaw_sd_deg
// (the heading estimate and its circular sd) and yaw_error_deg (estimate minus truth, wrapped).
void write_rows_csv(const std::string& path, const std::vector<LocalizationRow>& rows, bool heading_columns = false);

// The heading figures of a compass-less run under their summary.json names (NaN: unknown).
std::vector<std::pair<std::string, double>> heading_numbers(const LocalizationSummary& summary);

// The six error figures (mean, final, slope of the filter and of the odometry) under the names every
// report uses: summary.json and the studies' results.
std::vector<std::pair<std::string, double>> error_numbers(const LocalizationSummary& summary);

// Summary keys plus free-form `extra` strings (backend, seed, conversion ...); numbers that are not
// finite are written as null.
void write_summary_json(const std::string& path, const LocalizationSummary& summary,
                        const std::map<std::string, std::string>& extra_strings,
                        const std::map<std::string, double>& extra_numbers);

// A few human-readable lines: errors, slopes, their ratios, particles, speed, counters.
std::string format_summary(const LocalizationSummary& summary);

struct PlotFiles {
    std::string trajectory_png, error_png;  // error_png "" when the flight has no ground truth
};

// A reference track drawn as points beside the estimates (a camera's GPS fixes): one map pixel per
// result row, NaN where the row has none. It is no ground truth and enters no error.
struct ReferenceTrack {
    std::string title;                        // the legend, e.g. "camera GPS (reference)"
    std::vector<std::array<double, 2>> px;    // per row; empty: no track
};

// Draws both plots into `folder` with gnuplot (run as a subprocess). The map is drawn under the
// trajectories, downscaled to at most 1000 pixels. Throws trn::Error when gnuplot is missing or fails
// (this is the only step that needs it). `odometry_title`: the odometry's legend (what the run used:
// "visual odometry", "odometry (folder)" ...).
PlotFiles plot_run(const std::string& folder, const std::vector<LocalizationRow>& rows, const LocalizationSummary& summary,
                   GrayView map, double metres_per_pixel, const std::string& title, const ReferenceTrack& reference = {},
                   const std::string& odometry_title = "odometry");

}  // namespace trn::localize
TRN_API_END
