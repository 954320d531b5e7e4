#pragma once
// The online localizer: what a robot embeds. Built once from the map, a scoring backend and the
// filter's settings; fed one Observation per camera frame as frames come; answers each with an
// Estimate. Every localization in trnkit (the CLI's localize and demo, the studies, the C API and
// Python) steps this class, so the same inputs give the same estimates bit for bit everywhere.
//
// Conventions (trn/scoring.hpp): map pixels, x east, y south, pixel centres at integers; yaw and
// headings in radians, clockwise from north (compass heading of the frame's top edge).
#include <chrono>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>

#include "trn/backend.hpp"
#include "trn/filter/nadir_warp.hpp"
#include "trn/filter/particle_filter.hpp"
#include "trn/filter/scorer.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// A camera's horizontal field of view the Localizer takes, degrees (outside: a unit mistake).
inline constexpr double kMinCameraHfovDeg = 5, kMaxCameraHfovDeg = 170;

struct LocalizerConfig {
    filter::FilterConfig filter;             // metres_per_pixel is replaced by the map's
    filter::BackendScorerOptions scoring;    // template width, dense or sparse scoring (min_valid_fraction: filter.update's)
    double start_x = NAN, start_y = NAN;     // map pixels: the last known position (required before the first step)
    // Centre of the initial headings; NaN: the first step's heading. Without a compass
    // (filter.heading = HeadingMode::None) the yaw prior: NaN uniform, else Gaussian around it with
    // filter.init_heading_sd_deg.
    double start_heading_rad = NAN;
    double camera_hfov_deg = NAN;            // horizontal field of view, needed when steps give altitude, not scale
    double max_tilt_deg = filter::kDefaultMaxTiltDeg;  // steps with an attitude tilted further are not scored
    // Latitude / longitude of map pixel (0, 0) on a north-up map: estimates then also come as
    // latitude / longitude (sim::map_pixel_to_latlon's local projection). None: map pixels only.
    std::optional<sim::GeoOrigin> map_origin;
    // Without a compass (filter.heading = HeadingMode::None) and with a uniform yaw prior
    // (start_heading_rad NaN), the most particles (and, under ours, the initial set) is at least
    // this: the initial set must cover every yaw over the start disc. 0: filter.max_particles, as
    // with a compass. localizer_profile sets it (localizer_defaults.hpp); LocalizerConfig{} leaves 0.
    std::size_t compassless_max_particles = 0;
    // Without a compass and with a yaw prior (start_heading_rad given), the prior's sd in degrees when
    // filter.init_heading_sd_deg is NaN (NaN here too: motion.eps_rot_deg, as with a compass).
    double compassless_yaw_sd_deg = NAN;
    // Visual odometry online (issue 43 item 4): a step whose odometry_east_m or odometry_north_m is NaN
    // (not given) takes its odometry from its own frame against the previous frame's, by the rules of
    // `trnkit localize --odometry visual` (filter::VisualOdometryTrack: scaled by the previous frame's
    // map_px_per_camera_px or altitude, turned by the previous step's heading_rad, or without a compass
    // by its own summed rotations, which then give odometry_yaw_rad). Odometry the caller gives is
    // used as given. Every frame is tracked either way, so the visual odometry is ready when the
    // caller's stops. Estimate::odometry_source says which was used. Default: kDefaultVisualOdometry.
    bool visual_odometry = false;

    void validate() const;  // throws trn::Error naming the field ("start_x", "camera_hfov_deg", ...)
};

// The presets (localizer_profile), the front ends' shared defaults and the rules above applied:
// trn/localize/localizer_defaults.hpp.

// One camera frame and what the other sensors said since the previous one.
struct Observation {
    GrayView frame;                                       // grey, as taken; empty: no image this step
    double map_px_per_camera_px = NAN;                    // the frame's scale; NaN: from altitude_agl_m and the camera
    double altitude_agl_m = NAN;                          // height above the ground, metres
    double odometry_east_m = NAN, odometry_north_m = NAN; // displacement since the previous step (NaN: lost)
    double heading_rad = NAN;                             // compass heading; NaN: none this step
    // Without a compass (config.filter.heading = HeadingMode::None) heading_rad is ignored, the
    // odometry's displacement is in the previous frame's own axes (as if its top pointed north:
    // odometry_north_m forward, towards the frame top; odometry_east_m to its right), and this is
    // the frame's rotation since the previous step, clockwise (NaN: unknown this step).
    double odometry_yaw_rad = NAN;
    bool has_attitude = false;                            // roll/pitch measured: a tilted frame is warped to nadir
    double roll_rad = 0, pitch_rad = 0;
    double time_s = NAN;                                  // when the frame was taken, seconds on any one clock
                                                          // (NaN: unknown); velocity needs two steps with times;
                                                          // the interval scales the motion noise and a lost
                                                          // odometry's held step (FilterInput::dt_s); a time before
                                                          // the previous step's counts as unknown
};

struct Estimate {
    double x = 0, y = 0, yaw = 0;                   // weighted mean, map pixels / radians
    double best_x = 0, best_y = 0, best_yaw = 0, best_ncc = 0;  // the best-scoring particle
    double spread_m = 0;                            // weighted rms distance of the particles from (x, y)
    double yaw_sd = 0;                              // circular sd of the particles' yaws, radians (the heading's spread)
    // The position's uncertainty: the particles' weighted covariance, in the map's frame (pixels^2,
    // x east, y south) and in metres^2 north/east (cov_ne: the north-east term). eph_m: 1 sigma on
    // its worst axis (square root of the largest eigenvalue). How well it covers the truth on the real
    // flights: docs/RESULTS.md, "Uncertainty".
    double cov_xx_px2 = 0, cov_xy_px2 = 0, cov_yy_px2 = 0;
    double cov_nn_m2 = 0, cov_ne_m2 = 0, cov_ee_m2 = 0;
    double eph_m = 0;
    double latitude_deg = NAN, longitude_deg = NAN;  // of (x, y), with config.map_origin
    double time_s = NAN;                             // the observation's
    // Velocity over the ground from this and the previous step's estimates and times (NaN: no
    // previous step with a time), m/s, and its variance per axis (the two positions' average
    // variance per axis, taken independent, over dt^2).
    double vel_north_mps = NAN, vel_east_mps = NAN, vel_var_m2ps2 = NAN;
    std::size_t particles = 0, off_map = 0;         // scored this step / of them with no valid score
    double frame_weight = 1;                        // the update's tempering exponent (filter::UpdateModel): 1 the frame
                                                    // believed whole, smaller: believed in part, 0: it told nothing
    bool frame_missing = false;                     // no frame scored (none given, or too oblique)
    bool too_oblique = false;                       // the attitude tilted the camera beyond max_tilt_deg
    double tilt_deg = 0;                            // of the optical axis from the vertical (0 without attitude)
    bool odometry_lost = false, reinitialised = false;
    // Which odometry this step used (static strings): "given" (the caller's), "none" (none given,
    // visual odometry off), or with LocalizerConfig::visual_odometry the frame's: "visual:start",
    // "visual:features", "visual:phase", "visual:lost", "visual:no-frame" (filter::VisualOdometryTrack).
    const char* odometry_source = "none";
    filter::LockReport lock;                        // the lock monitor's evidence and verdict
    double score_ms = 0, step_ms = 0;               // scoring calls / the whole step, wall time
};

// The lock monitor's verdict in one word, the strongest first: "none" (not assessed: monitor off or
// no frame), "lost" (the monitor's verdict, or the filter redrew its particles), "fix",
// "inconsistent", "weak", "unknown" (not judged: no fix since the start, the last loss or the last
// weak step, no random place on the map to compare the best score with, or the frame told nothing),
// "ok" (a fix vouches for the track and this frame's best place stands out).
const char* lock_state_name(const filter::LockReport& lock);

class Localizer {
public:
    // The map is uploaded to `backend` here (the view need not outlive the constructor); the
    // backend must outlive the Localizer.
    // `valid`: the map's no-data (255/non-zero valid, 0 not; the map's size), or empty: every pixel
    // valid. Samples on no-data are left out of every score (trn/backend.hpp, upload_map).
    Localizer(GrayView map, double metres_per_pixel, Backend& backend, const LocalizerConfig& config, GrayView valid = {});
    ~Localizer();
    Localizer(const Localizer&) = delete;
    Localizer& operator=(const Localizer&) = delete;

    // Scatters the particles around (x, y) map pixels, headings around heading_rad (NaN: kept
    // unknown until a step brings one). Optional: the first step starts at config.start_* itself.
    void start(double x, double y, double heading_rad);
    // Re-anchors the filter on a new position (e.g. a GNSS fix came back): its particles scattered
    // uniformly within radius_m metres of (x, y) map pixels, keeping the configuration; headings
    // around heading_rad (NaN: without a compass the yaw learnt so far, with one the next step's
    // heading). The lock state reads "unknown" again until the next fix; no velocity across it.
    // Before the first step it starts the filter there. Throws trn::Error naming what is wrong
    // (radius_m not > 0, or the disc of radius_m around (x, y) off the map).
    void reanchor(double x, double y, double radius_m, double heading_rad = NAN);
    Estimate step(const Observation& observation);

    bool started() const { return started_; }
    const filter::FilterCounters& counters() const;
    const std::vector<filter::Particle>& particles() const;
    const LocalizerConfig& config() const { return config_; }
    double metres_per_pixel() const { return mpp_; }
    const DeviceInfo& backend_info() const { return backend_.info(); }
    int map_width() const { return map_width_; }
    int map_height() const { return map_height_; }

private:
    void add_uncertainty(const filter::Estimate& f, double time_s, Estimate& e);
    void check_on_map(double x, double y, double radius_m, const char* what) const;  // throws naming `what` and the map's size
    void check_observation(const Observation& o) const;
    // The frame's visual odometry as this step's input (LocalizerConfig::visual_odometry); returns the source label.
    const char* visual_odometry(const Observation& o, filter::FilterInput& in);

    LocalizerConfig config_;
    double mpp_;
    Backend& backend_;
    std::unique_ptr<filter::BackendScorer> scorer_;
    std::unique_ptr<filter::ParticleFilter> filter_;
    int map_width_ = 0, map_height_ = 0;
    bool started_ = false;
    bool heading_known_ = false;  // a heading was given (start or step): compass mode may score frames
    Estimate previous_;  // for the velocity (time_s NaN: none)
    struct VisualOdometryState;
    std::unique_ptr<VisualOdometryState> visual_;  // with config.visual_odometry
};

}  // namespace trn::localize
TRN_API_END
