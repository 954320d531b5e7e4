#pragma once
// A whole flight localized at once, built on the online Localizer (localizer.hpp): one row per
// filter step with the ground truth and odometry next to the estimate, and a summary of errors the
// way the dissertation gives them (mean, final, and the slope of a least-squares line of error over
// distance flown). The flight is an AIR folder or a simulated scenario, with its own odometry or
// visual odometry computed from the frames.
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "trn/filter/flight_source.hpp"
#include "trn/filter/visual_odometry.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

struct LocalizationRow {
    std::size_t frame = 0;
    double time_s = 0, distance_m = 0;                 // distance flown along the ground truth
    double truth_x = NAN, truth_y = NAN;               // map pixels
    double odometry_x = NAN, odometry_y = NAN;         // odometry placed on the map at the start
    double estimate_x = 0, estimate_y = 0, estimate_yaw = 0;
    double estimate_yaw_sd = 0;                        // circular sd of the particles' yaws, radians
    double truth_yaw = NAN;                            // radians, with the ground truth
    double best_x = 0, best_y = 0;
    double error_m = NAN, odometry_error_m = NAN;
    double cov_nn_m2 = 0, cov_ne_m2 = 0, cov_ee_m2 = 0;  // the estimate's position covariance (Estimate)
    double error_sigmas = NAN;  // the error in the covariance's sigmas (Mahalanobis distance; inf: a point cloud)
    std::size_t particles = 0, off_map = 0;
    double frame_weight = 1;  // how much of the frame's evidence the update took (filter::UpdateModel; 0: none)
    double score_ms = 0, step_ms = 0;
    bool odometry_lost = false, frame_missing = false, reinitialised = false;
    filter::LockReport lock;  // the lock monitor's evidence and verdict this step (default: not assessed)
    double tilt_deg = 0;                             // of the camera from nadir (measured roll/pitch)
    bool too_oblique = false;                        // tilted beyond the limit: not scored (not frame_missing)
    double estimate_lat = NAN, estimate_lon = NAN;   // degrees, when the map is georeferenced
    std::string odometry_source;                     // the sample's: "simulated", "folder", "visual:features" ...
};

struct LocalizationSummary {
    std::size_t steps = 0;
    double filter_mean_error_m = NAN, odometry_mean_error_m = NAN;
    double filter_final_error_m = NAN, odometry_final_error_m = NAN;
    double filter_error_slope_m_per_km = NAN, odometry_error_slope_m_per_km = NAN;
    double filter_error_intercept_m = NAN, odometry_error_intercept_m = NAN;  // of the same lines, at 0 km
    // The same errors over time (seconds from the first step), as two lines broken at
    // kErrorSlopeBreakS (the dissertation's Fig 3.9 breaks its trend lines at 35 s of flight):
    // least-squares slopes in m/s of the steps before the break and of those from it on
    // (fit_broken_line; NaN where a side has fewer than two steps with errors).
    double filter_slope_before_break_m_per_s = NAN, filter_slope_after_break_m_per_s = NAN;
    double odometry_slope_before_break_m_per_s = NAN, odometry_slope_after_break_m_per_s = NAN;
    double distance_m = 0;
    double mean_particles = 0;
    double frames_per_second = 0;   // filter steps per second of wall time (sampling + scoring + estimate)
    double mean_score_ms = 0;
    std::size_t frames_too_oblique = 0;  // not scored for tilt; counters.frames_missing excludes them
    // The heading estimate (reported for compass-less runs): error of the estimate's yaw against the
    // true yaw (mean |error| over the steps with truth, final), final circular sd of the yaws, and
    // the error after convergence: from the first step whose yaw sd is below kConvergedYawSdDeg and
    // whose lock-monitor verdict is a fix (position confident; yaw alone when no step was assessed) on.
    double mean_yaw_error_deg = NAN, final_yaw_error_deg = NAN, final_yaw_sd_deg = NAN;
    double converged_from_frame = NAN;        // frame of that first step (NaN: never converged)
    double converged_mean_error_m = NAN;      // mean position error from that step on
    double converged_mean_yaw_error_deg = NAN;
    // Calibration of the covariance: share of the steps with truth whose truth lies inside the 1- and
    // 2-sigma ellipses (a 2-D Gaussian: 39.3 % and 86.5 %); more: under-confident, less: over-confident.
    double inside_1sigma = NAN, inside_2sigma = NAN;
    filter::FilterCounters counters;
};

// How a run was set up, for its report.
struct RunInfo {
    std::string backend, device;           // the scoring backend's name and device
    std::string conversion, sampling;      // the filter's (Conversion::to_string, to_string(SamplingMethod))
    double sparse = 1;                     // share of template pixels scored (1 = dense)
    std::uint64_t seed = 1;
    double filter_rate_hz = 0;
    int template_width = 0;
    std::size_t stride = 1, frames = 0;    // every stride-th camera frame is a step; frames expected (0: unknown)
    double start_x = NAN, start_y = NAN;   // the start used (the first row's truth when the spec gave none)
    bool visual_odometry = false;
    filter::VisualOdometrySource::Counts visual_odometry_counts;
    std::string heading = "compass";       // "none": compass-less (yaw estimated; the report adds its columns and numbers)
};

struct LocalizationResult {
    std::vector<LocalizationRow> rows;
    LocalizationSummary summary;
    RunInfo run;
};

// Progress: (samples done, samples expected or 0).
using ProgressFn = std::function<void(std::size_t, std::size_t)>;
// After each filter step: its row (estimate_lat/lon filled when the map is georeferenced) and estimate.
using StepFn = std::function<void(const LocalizationRow&, const Estimate&)>;

// A recorded flight: an AIR folder (metadata.csv and frames).
struct AirFolderFlight {
    std::string folder;
    sim::Camera camera;     // hfov_deg gives each frame its scale by its own width; the size, see camera_size_stated
    double fps = 0;         // camera frame rate; 0: unknown, every row is a filter step at rate_hz
    double max_tilt_deg = filter::kDefaultMaxTiltDeg;
    // The camera's size is the folder's (flight.json states it): every frame must be a resized view
    // of it. False (a folder without flight.json): every frame must be one of the first frame.
    bool camera_size_stated = false;
};

// A flight simulated over `world` (the scene the camera sees, kept alive by the caller).
struct SimulatedFlight {
    const sim::Map* world = nullptr;
    sim::FlightConfig flight;
};

enum class OdometryKind {
    Recorded,  // the flight's own: an AIR folder's SvoX/SvoY, the simulator's drifting odometry
    Visual,    // computed frame to frame from the camera (visual_odometry.hpp)
};

struct LocalizationSpec {
    std::variant<AirFolderFlight, SimulatedFlight> flight;
    OdometryKind odometry = OdometryKind::Recorded;
    double rate_hz = 5;              // filter steps per second (every fps/rate-th frame)
    LocalizerConfig localizer;       // start_x/start_y NaN: the first row's ground truth
    // Latitude/longitude of a map pixel when the map is georeferenced (fills the rows' estimate_lat/lon).
    std::function<sim::LatLon(double x, double y)> to_latlon;
};

// What a run reports while it goes: its set-up before the first step, the flight source's
// warnings, and progress.
struct RunHooks {
    std::function<void(const RunInfo&)> started;
    std::function<void(const std::string&)> warning;
    ProgressFn progress;
    StepFn step;  // e.g. streaming each estimate out (trnkit localize --mavlink)
};

// Localizes the whole flight of `spec` on `map` (metres_per_pixel: the map's) with `backend`.
// Throws trn::Error naming the spec field (flight.folder, start_x ...) or the dataset's file:line.
LocalizationResult run_localization(const LocalizationSpec& spec, GrayView map, double metres_per_pixel, Backend& backend,
                                    const RunHooks& hooks = {});
// The same on a map with its resolution and no-data (sim::Map::valid).
LocalizationResult run_localization(const LocalizationSpec& spec, const sim::Map& map, Backend& backend, const RunHooks& hooks = {});

// The same over any flight source with a Localizer already built (tests, custom sources). Its start
// is config.start_*, else the first sample's ground truth.
LocalizationResult run_localization(filter::FlightSource& source, Localizer& localizer, const ProgressFn& progress = {},
                                    const StepFn& on_step = {});

// Least-squares line of y over x (NaN with fewer than two distinct x).
struct FittedLine {
    double slope = NAN, intercept = NAN;
};
FittedLine fit_line(const std::vector<double>& x, const std::vector<double>& y);
inline double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) { return fit_line(x, y).slope; }
// Two least-squares lines of y over x: one through the points with x < break_x, one through those
// with x >= break_x, each fitted on its own (not joined at the break); a side with fewer than two
// distinct x has NaN.
struct BrokenLine {
    FittedLine before, after;
};
BrokenLine fit_broken_line(const std::vector<double>& x, const std::vector<double>& y, double break_x);
// Where the summary's error lines over time break (LocalizationSummary::*_break_m_per_s): 35 s of
// flight, the break point of the dissertation's Fig 3.9.
inline constexpr double kErrorSlopeBreakS = 35;
// The lock monitor's counters: added to a command's extra summary-JSON numbers, and as one line
// for the console.
std::map<std::string, double> with_lock_numbers(const LocalizationSummary& summary, std::map<std::string, double> numbers);
std::string format_lock_summary(const LocalizationSummary& summary);
// The position error (east, south, metres) in sigmas of the covariance: sqrt(e' C^-1 e); +inf when
// the covariance is singular and the error is not zero.
double error_in_sigmas(double error_east_m, double error_north_m, double cov_nn_m2, double cov_ne_m2, double cov_ee_m2);
// Share of a 2-D Gaussian inside its k-sigma ellipse: 1 - exp(-k^2 / 2).
inline double gaussian_inside(double k) { return 1 - std::exp(-k * k / 2); }
LocalizationSummary summarise(const std::vector<LocalizationRow>& rows, const filter::FilterCounters& counters, double wall_s);
// Yaw sd (degrees) below which a compass-less run counts as converged (summary's converged_*).
inline constexpr double kConvergedYawSdDeg = 10.0;

}  // namespace trn::localize
TRN_API_END
