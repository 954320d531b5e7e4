#include "trn/localize/localizer.hpp"

#include <cstdio>

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
    if (!std::isnan(camera_hfov_deg) && !(camera_hfov_deg > 0 && camera_hfov_deg < 180))
        throw Error("localizer config: camera_hfov_deg must be in (0, 180) degrees, got " + number(camera_hfov_deg));
    if (!(max_tilt_deg >= 0 && max_tilt_deg < 90)) throw Error("localizer config: max_tilt_deg must be in [0, 90)");
    if (map_origin) sim::check_geo_origin(*map_origin, "localizer config: map_origin");  // the geodesy home's rule
    if (scoring.template_width < 0) throw Error("localizer config: scoring.template_width must be >= 0 (0: full width)");
}

Localizer::Localizer(GrayView map, double metres_per_pixel, Backend& backend, const LocalizerConfig& config, GrayView valid)
    : config_(config), mpp_(metres_per_pixel), backend_(backend) {
    if (!(metres_per_pixel > 0) || !std::isfinite(metres_per_pixel))
        throw Error("localizer: metres_per_pixel must be > 0, got " + number(metres_per_pixel));
    if (map.width < 2 || map.height < 2) throw Error("localizer: the map must be at least 2x2 pixels");
    config_.validate();
    config_.filter.metres_per_pixel = metres_per_pixel;
    config_.filter.validate();
    config_.scoring.min_valid_fraction = config_.filter.update.min_valid_fraction;  // one knob: the update's
    scorer_ = std::make_unique<filter::BackendScorer>(backend, map, config_.scoring, valid);
    filter_ = std::make_unique<filter::ParticleFilter>(*scorer_, config_.filter);
}

Localizer::~Localizer() = default;

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
    if (!std::isfinite(x) || !std::isfinite(y)) throw Error("localizer: start position must be finite map pixels");
    filter_->initialise(x, y, heading_rad);
    previous_ = Estimate{};  // no velocity across a restart
    started_ = true;
}

Estimate Localizer::step(const Observation& o) {
    const auto t0 = std::chrono::steady_clock::now();
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
                throw Error("localizer: a step without map_px_per_camera_px needs camera_hfov_deg in the config (and altitude_agl_m)");
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
