#pragma once
// Runs a ParticleFilter over a FlightSource and keeps one row per filter step, with the ground
// truth and odometry next to the estimate; summarises errors the way the dissertation does
// (mean, final, and the slope of a least-squares line of error over distance flown).
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "trn/filter/flight_source.hpp"
#include "trn/filter/particle_filter.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct LocalizationRow {
    std::size_t frame = 0;
    double time_s = 0, distance_m = 0;                 // distance flown along the ground truth
    double truth_x = NAN, truth_y = NAN;               // map pixels
    double odometry_x = NAN, odometry_y = NAN;         // odometry placed on the map at the start
    double estimate_x = 0, estimate_y = 0, estimate_yaw = 0;
    double best_x = 0, best_y = 0;
    double error_m = NAN, odometry_error_m = NAN;
    std::size_t particles = 0, off_map = 0;
    double score_ms = 0, step_ms = 0;
    bool odometry_lost = false, frame_missing = false, reinitialised = false;
    LockReport lock;  // the lock monitor's evidence and verdict this step (default: not assessed)
    double tilt_deg = 0;                             // of the camera from nadir (measured roll/pitch)
    bool too_oblique = false;                        // tilted beyond the limit: not scored (not frame_missing)
    double estimate_lat = NAN, estimate_lon = NAN;   // degrees, when the map is georeferenced (filled by the caller)
    std::string odometry_source;                     // the sample's: "simulated", "folder", "visual:features" ...
};

struct LocalizationSummary {
    std::size_t steps = 0;
    double filter_mean_error_m = NAN, odometry_mean_error_m = NAN;
    double filter_final_error_m = NAN, odometry_final_error_m = NAN;
    double filter_error_slope_m_per_km = NAN, odometry_error_slope_m_per_km = NAN;
    double filter_error_intercept_m = NAN, odometry_error_intercept_m = NAN;  // of the same lines, at 0 km
    double distance_m = 0;
    double mean_particles = 0;
    double frames_per_second = 0;   // filter steps per second of wall time (sampling + scoring + estimate)
    double mean_score_ms = 0;
    std::size_t frames_too_oblique = 0;  // not scored for tilt; counters.frames_missing excludes them
    FilterCounters counters;
};

struct LocalizationResult {
    std::vector<LocalizationRow> rows;
    LocalizationSummary summary;
};

// Progress: (samples done, samples expected or 0).
using ProgressFn = std::function<void(std::size_t, std::size_t)>;

// Initialises the filter at the first sample's ground truth ("the last known position"; a source
// without truth must be given `start_x`, `start_y`), then steps it once per sample. The initial
// headings centre on `start_heading_rad` (radians; NaN: the first magnetometer reading).
LocalizationResult run_localization(FlightSource& source, ParticleFilter& filter, const ProgressFn& progress = {},
                                    double start_x = NAN, double start_y = NAN, double start_heading_rad = NAN);

// Least-squares line of y over x (NaN with fewer than two distinct x).
struct FittedLine {
    double slope = NAN, intercept = NAN;
};
FittedLine fit_line(const std::vector<double>& x, const std::vector<double>& y);
inline double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) { return fit_line(x, y).slope; }
// The lock monitor's counters: added to a command's extra summary-JSON numbers, and as one line
// for the console.
std::map<std::string, double> with_lock_numbers(const LocalizationSummary& summary, std::map<std::string, double> numbers);
std::string format_lock_summary(const LocalizationSummary& summary);
LocalizationSummary summarise(const std::vector<LocalizationRow>& rows, const FilterCounters& counters, double wall_s);

}  // namespace trn::filter
TRN_API_END
