#include "trn/localize/localizer.hpp"

#include "trn/localize/localizer_defaults.hpp"

#include <cstdio>

#include "trn/detail/angles.hpp"
#include "trn/filter/visual_odometry_track.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/detail/covariance2.hpp"
#include "trn/error.hpp"
#include "trn/sim/camera.hpp"
#include "trn/sim/geodesy.hpp"

namespace trn::localize {
namespace {


std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace

// A lost step is usually also weak or inconsistent. assess() always measures the drift, so no drift
// means the step was not assessed. "ok" needs evidence (issue 43): a fix since the start, the last
// loss or the last weak step (after an odometry glitch the old fix vouches for nothing), and a
// contrast measured this step; a redraw is a loss; a frame that told nothing, or no probe scored
// (NaN contrast), leaves the position unjudged.
const char* lock_state_name(const filter::LockReport& l) {
    if (std::isnan(l.drift_m)) return "none";
    if (l.lost || l.redrawn) return "lost";
    if (l.confident) return "fix";
    if (l.inconsistent) return "inconsistent";
    if (l.weak) return "weak";
    if (l.blind || std::isnan(l.contrast) || !l.fixed_before) return "unknown";
    return "ok";
}

void LocalizerConfig::validate() const {
    if (std::isnan(start_x) != std::isnan(start_y)) throw Error("localizer config: start_x and start_y go together");
    if (!std::isnan(start_x) && !(std::isfinite(start_x) && std::isfinite(start_y)))
        throw Error("localizer config: start_x, start_y must be finite map pixels");
    if (!std::isnan(start_heading_rad) && !std::isfinite(start_heading_rad))
        throw Error("localizer config: start_heading_rad must be finite (or NaN: the first step's heading)");
    if (!std::isnan(camera_hfov_deg) && !(camera_hfov_deg >= kMinCameraHfovDeg && camera_hfov_deg <= kMaxCameraHfovDeg))
        throw Error("localizer config: camera_hfov_deg (the camera's horizontal field of view) must be in [" + number(kMinCameraHfovDeg) + ", " +
                    number(kMaxCameraHfovDeg) + "] degrees, got " + number(camera_hfov_deg) +
                    (camera_hfov_deg > 0 && camera_hfov_deg < kMinCameraHfovDeg ? " (radians? it is in degrees)" : ""));
    if (!(max_tilt_deg >= 0 && max_tilt_deg < 90)) throw Error("localizer config: max_tilt_deg must be in [0, 90)");
    if (map_origin) sim::check_geo_origin(*map_origin, "localizer config: map_origin");  // the geodesy home's rule
    if (scoring.template_width < 0) throw Error("localizer config: scoring.template_width must be >= 0 (0: full width)");
}

// The frame's visual odometry, as `trnkit localize --odometry visual` turns it into the Localizer's
// input: the track from the first frame (VisualOdometryTrack), its increments (OdometryIncrements)
// and, without a compass, the same in the previous frame's axes with the yaw's change.
struct Localizer::VisualOdometryState {
    explicit VisualOdometryState(bool own_yaw) : track({}, own_yaw) {}
    filter::VisualOdometryTrack track;
    OdometryIncrements increments;
    CompasslessOdometry compassless;
};

Localizer::Localizer(GrayView map, double metres_per_pixel, Backend& backend, const LocalizerConfig& config, GrayView valid)
    : config_(resolved_config(config)), mpp_(metres_per_pixel), backend_(backend), map_width_(map.width), map_height_(map.height) {
    if (!(metres_per_pixel > 0) || !std::isfinite(metres_per_pixel))
        throw Error("localizer: metres_per_pixel must be > 0, got " + number(metres_per_pixel));
    if (map.width < 2 || map.height < 2) throw Error("localizer: the map must be at least 2x2 pixels");
    config_.validate();
    if (!std::isnan(config_.start_x)) check_on_map(config_.start_x, config_.start_y, config_.filter.init_radius_m, "start (start_x, start_y)");
    config_.filter.metres_per_pixel = metres_per_pixel;
    config_.filter.validate();
    config_.scoring.min_valid_fraction = config_.filter.update.min_valid_fraction;  // one knob: the update's
    scorer_ = std::make_unique<filter::BackendScorer>(backend, map, config_.scoring, valid);
    filter_ = std::make_unique<filter::ParticleFilter>(*scorer_, config_.filter);
    if (config_.visual_odometry) visual_ = std::make_unique<VisualOdometryState>(config_.filter.heading == filter::HeadingMode::None);
}

Localizer::~Localizer() = default;

const char* Localizer::visual_odometry(const Observation& o, filter::FilterInput& in) {
    const bool given = !std::isnan(o.odometry_east_m) && !std::isnan(o.odometry_north_m);
    if (!visual_) return given ? "given" : "none";
    // Every frame is tracked (the reference stays the last frame), the caller's odometry wins when given.
    if (!in.frame.empty() && (in.frame.width < 16 || in.frame.height < 16))
        throw Error("localizer: visual_odometry tracks each frame, and this one is " + std::to_string(in.frame.width) + "x" +
                    std::to_string(in.frame.height) + " px: at least 16x16 is needed (or turn visual_odometry off)");
    const bool compass = config_.filter.heading == filter::HeadingMode::Compass;
    const double metres_per_px = in.frame.empty() ? NAN : in.map_px_per_camera_px * mpp_;
    const filter::VisualOdometryTrack::Step v = visual_->track.next(in.frame, metres_per_px, compass ? o.heading_rad : NAN);
    const OdometryIncrements::Step step = visual_->increments.next(v.east_m, v.north_m);
    const CompasslessOdometry::Step own = compass ? CompasslessOdometry::Step{} : visual_->compassless.next(step, v.yaw_rad);
    if (given) return "given";
    if (compass) in.odometry_east_m = step.east_m, in.odometry_north_m = step.north_m;
    else in.odometry_east_m = own.right_m, in.odometry_north_m = own.forward_m, in.odometry_yaw_rad = own.rotation_rad;
    return v.source;
}

// Map pixels (x east, y south) to metres north/east: north = -y, so the cross term changes sign.
void Localizer::add_uncertainty(const filter::Estimate& f, double time_s, Estimate& e) {
    const double m2 = mpp_ * mpp_;
    e.cov_xx_px2 = f.cov_xx, e.cov_xy_px2 = f.cov_xy, e.cov_yy_px2 = f.cov_yy;
    e.cov_ee_m2 = f.cov_xx * m2, e.cov_nn_m2 = f.cov_yy * m2, e.cov_ne_m2 = -f.cov_xy * m2;
    e.eph_m = largest_sigma(e.cov_nn_m2, e.cov_ne_m2, e.cov_ee_m2);
    if (config_.map_origin) {  // map pixels are metres east / south of the origin times mpp
        const sim::LatLon ll = sim::local_m_to_latlon(*config_.map_origin, e.x * mpp_, e.y * mpp_);
        e.latitude_deg = ll.latitude_deg, e.longitude_deg = ll.longitude_deg;
    }
    e.time_s = time_s;
    const double dt = time_s - previous_.time_s;
    if (dt > 0) {  // NaN on either side: no velocity
        e.vel_east_mps = (e.x - previous_.x) * mpp_ / dt, e.vel_north_mps = -(e.y - previous_.y) * mpp_ / dt;
        const double per_axis = (e.cov_ee_m2 + e.cov_nn_m2 + previous_.cov_ee_m2 + previous_.cov_nn_m2) / 4;
        e.vel_var_m2ps2 = 2 * per_axis / (dt * dt);
    }
    previous_ = e;
}

const filter::FilterCounters& Localizer::counters() const { return filter_->counters(); }
const std::vector<filter::Particle>& Localizer::particles() const { return filter_->particles(); }

void Localizer::start(double x, double y, double heading_rad) {
    check_on_map(x, y, config_.filter.init_radius_m, "start position");
    filter_->initialise(x, y, heading_rad);
    heading_known_ = std::isfinite(heading_rad);
    previous_ = Estimate{};  // no velocity across a restart
    started_ = true;
}

// A start (or re-anchor) whose disc of radius_m misses the map entirely: no particle could start on
// it (issue 43: a start far off the map was accepted).
void Localizer::check_on_map(double x, double y, double radius_m, const char* what) const {
    const double r = radius_m / mpp_;
    if (!(std::isfinite(x) && std::isfinite(y) && x >= -r && x <= map_width_ - 1 + r && y >= -r && y <= map_height_ - 1 + r))
        throw Error(std::string("localizer: ") + what + " " + number(x) + ", " + number(y) + " is outside the " + std::to_string(map_width_) +
                    "x" + std::to_string(map_height_) + " px map by more than its radius (" + number(radius_m) +
                    " m): no particle would start on the map (map pixels: x east from 0, y south from 0)");
}

void Localizer::reanchor(double x, double y, double radius_m, double heading_rad) {
    if (!(radius_m > 0) || !std::isfinite(radius_m))
        throw Error("localizer: re-anchor radius_m must be > 0 metres (how far the true position may be from the fix), got " + number(radius_m));
    check_on_map(x, y, radius_m, "re-anchor position");
    if (!std::isnan(heading_rad) && !std::isfinite(heading_rad)) throw Error("localizer: re-anchor heading_rad must be finite radians (or NaN)");
    filter_->reanchor(x, y, radius_m, heading_rad);
    if (std::isfinite(heading_rad)) heading_known_ = true;
    previous_ = Estimate{};  // no velocity across a jump
    started_ = true;
}

// The traps of issue 43 that one observation shows: refused, naming the input in user terms.
void Localizer::check_observation(const Observation& o) const {
    if (std::isfinite(o.map_px_per_camera_px) && std::isfinite(o.altitude_agl_m))
        throw Error("localizer: a step gives both the frame's scale (map pixels per frame pixel) and altitude_agl_m; give one (which "
                    "should win is ambiguous)");
    if (!std::isnan(o.map_px_per_camera_px) && !(o.map_px_per_camera_px > 0 && std::isfinite(o.map_px_per_camera_px)))
        throw Error("localizer: the frame's scale " + number(o.map_px_per_camera_px) + " (map pixels per frame pixel) must be > 0");
    // The odometry's meaning changes with the heading mode (localizer.hpp, Observation): an input of
    // the other mode says the caller means the other one.
    const bool compass = config_.filter.heading == filter::HeadingMode::Compass;
    if (!compass && std::isfinite(o.heading_rad))
        throw Error("localizer: heading_rad given to a Localizer without a compass (heading \"none\"), which does not use it: its "
                    "odometry is in the previous frame's axes (forward, right) with odometry_yaw_rad the frame's rotation; for "
                    "east/north odometry with a compass heading, use heading \"compass\"");
    if (compass && std::isfinite(o.odometry_yaw_rad))
        throw Error("localizer: odometry_yaw_rad given to a Localizer with a compass (heading \"compass\"), which does not use it: its "
                    "odometry is east/north and each step's heading_rad sets the yaw; for odometry in the frame's own axes, use heading "
                    "\"none\"");
    if (o.has_attitude) {
        for (const auto& [v, name] : {std::pair{o.roll_rad, "roll"}, {o.pitch_rad, "pitch"}})
            if (std::abs(v) > 2 * kPi)
                throw Error(std::string("localizer: attitude ") + name + " " + number(v) +
                            ": beyond 2 pi, degrees? The attitude is in radians (roll_rad, pitch_rad)");
    }
}

Estimate Localizer::step(const Observation& o) {
    const auto t0 = std::chrono::steady_clock::now();
    check_observation(o);
    if (!started_) {
        if (std::isnan(config_.start_x))
            throw Error("localizer: start_x, start_y: required (the last known position, map pixels) before the first step");
        const bool compass = config_.filter.heading == filter::HeadingMode::Compass;
        start(config_.start_x, config_.start_y, std::isnan(config_.start_heading_rad) && compass ? o.heading_rad : config_.start_heading_rad);
    }
    Estimate e;
    filter::FilterInput in;
    in.odometry_east_m = o.odometry_east_m, in.odometry_north_m = o.odometry_north_m;
    in.heading_rad = o.heading_rad;
    in.odometry_yaw_rad = o.odometry_yaw_rad;
    in.frame = o.frame.empty() ? GrayView{} : o.frame;
    in.map_px_per_camera_px = o.map_px_per_camera_px;
    // NaN on either side, or a clock that went backwards (reset): unknown, as for the velocity.
    if (const double dt = o.time_s - previous_.time_s; dt >= 0) in.dt_s = dt;
    GrayImage level;  // the nadir view of a tilted frame
    if (!o.frame.empty()) {
        if (!std::isfinite(o.map_px_per_camera_px)) {
            if (std::isnan(config_.camera_hfov_deg))
                throw Error("localizer: a frame's scale: give its height above the ground (altitude_agl_m) and the camera's field of view "
                            "(camera_hfov_deg in the config), or the scale itself (map pixels per frame pixel)");
            if (!(o.altitude_agl_m > 0))
                throw Error("localizer: altitude_agl_m " + number(o.altitude_agl_m) +
                            " m: a frame needs its height above the ground (> 0 m), or its scale (map pixels per frame pixel)");
            // The scale of this frame's own pixels: the focal length in pixels grows with the width.
            const sim::Camera own{o.frame.width, o.frame.height, config_.camera_hfov_deg};
            in.map_px_per_camera_px = sim::template_scale(own, o.altitude_agl_m, mpp_);
        }
        if (o.has_attitude) {  // the AIR flight source's rule (filter::level_frame)
            filter::LevelledFrame l = filter::level_frame(o.frame, config_.camera_hfov_deg, o.roll_rad, o.pitch_rad, config_.max_tilt_deg);
            e.tilt_deg = l.tilt_deg, e.too_oblique = l.too_oblique;
            level = std::move(l.image);
            if (e.too_oblique) in.frame = {};
            else if (!level.pixels.empty()) in.frame = level.view();
        }
    }
    // A compass Localizer that has never had a heading scores its frames at random yaws (issue 43:
    // 45 m instead of 3, silently): refused. Steps without a frame only move the particles.
    if (std::isfinite(o.heading_rad)) heading_known_ = true;
    if (config_.filter.heading == filter::HeadingMode::Compass && !heading_known_ && !in.frame.empty())
        throw Error("localizer: heading \"compass\" scores a frame at the compass heading, and none was ever given: no heading_rad "
                    "in any step and no start_heading_rad in the config; give one, or use heading \"none\" (no compass: the yaw is "
                    "estimated)");
    e.odometry_source = visual_odometry(o, in);
    const filter::StepReport rep = filter_->step(in);
    e.x = rep.estimate.x, e.y = rep.estimate.y, e.yaw = rep.estimate.yaw;
    e.best_x = rep.estimate.best_x, e.best_y = rep.estimate.best_y, e.best_yaw = rep.estimate.best_yaw, e.best_ncc = rep.estimate.best_ncc;
    e.spread_m = rep.estimate.spread_px * mpp_;
    add_uncertainty(rep.estimate, o.time_s, e);
    e.yaw_sd = rep.estimate.yaw_sd;
    e.particles = rep.particles, e.off_map = rep.off_map, e.frame_weight = rep.frame_weight;
    e.frame_missing = rep.frame_missing;
    e.odometry_lost = rep.odometry_lost, e.reinitialised = rep.reinitialised;
    e.lock = rep.lock;
    e.score_ms = rep.score_ms;
    e.step_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return e;
}

}  // namespace trn::localize
