#include "trn/sim/flight.hpp"

#include <algorithm>
#include <cmath>

#include "random.hpp"
#include "trn/error.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

// Half the diagonal of the camera footprint on the ground, metres (level camera).
double footprint_radius_m(const Camera& c, double altitude_m) {
    const double mpp_cam = altitude_m / c.focal_px();  // metres per camera pixel
    return 0.5 * std::hypot(c.width, c.height) * mpp_cam;
}

// Distance (metres) the trajectory keeps from the map's edges: the whole footprint stays on the map
// at the highest altitude, with room for roll/pitch wobble.
double edge_margin_m(const FlightConfig& cfg) {
    const double top = cfg.scenario.max_altitude_m();
    const double wobble = top * std::tan(3 * cfg.camera_roll_pitch_sd_deg * kDeg);
    return footprint_radius_m(cfg.camera, top) + wobble + 5;
}

Trajectory make_trajectory(const Map& map, const FlightConfig& cfg) {
    cfg.camera.validate();
    if (!(cfg.scenario.altitude_m > 0)) throw Error("flight: altitude must be > 0");
    if (!(cfg.scenario.other_altitude_m >= 0)) throw Error("flight: other_altitude_m must be >= 0");
    if (!(cfg.scenario.fps > 0)) throw Error("flight: fps must be > 0");
    cfg.scenario.realism.validate();
    const double top = cfg.scenario.max_altitude_m();
    const double margin = edge_margin_m(cfg);
    if (map.width_m() < 2 * margin + 20 || map.height_m() < 2 * margin + 20)
        throw Error("flight: the map (" + std::to_string(map.width_m()) + " x " + std::to_string(map.height_m()) +
                    " m) is too small for the camera footprint at " + std::to_string(top) +
                    " m (needs more than " + std::to_string(2 * margin + 20) + " m each way)");
    return Trajectory(cfg.scenario.shape, cfg.scenario.nominal_size_m, cfg.scenario.speed_mps, margin, margin,
                      map.width_m() - margin, map.height_m() - margin);
}

OdometryConfig odometry_config(const FlightConfig& config) {
    OdometryConfig o = config.odometry;
    o.seed ^= detail::mix64(config.seed);
    o.heading_walk_deg_per_sqrt_s += config.scenario.realism.odometry_heading_walk_deg_per_sqrt_s;
    o.scale_walk_per_sqrt_s += config.scenario.realism.odometry_scale_walk_per_sqrt_s;
    return o;
}

}  // namespace

double fitting_map_edge_m(const FlightConfig& cfg) {
    const Scenario& s = cfg.scenario;
    if (!s.one_loop) return std::ceil((s.nominal_size_m * 1.1 + 2 * footprint_radius_m(cfg.camera, s.max_altitude_m()) + 100) / 100) * 100;
    // Measure the loop's extent at full size (an area far larger than the loop: nothing shrinks).
    const Trajectory loop(s.shape, s.nominal_size_m, s.speed_mps, 0, 0, 1e7, 1e7);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (double d = 0; d <= loop.loop_length_m(); d += 0.5) {
        const TrajectoryState st = loop.at(d / s.speed_mps);
        x0 = std::min(x0, st.x_m), x1 = std::max(x1, st.x_m), y0 = std::min(y0, st.y_m), y1 = std::max(y1, st.y_m);
    }
    return std::ceil((std::max(x1 - x0, y1 - y0) + 2 * edge_margin_m(cfg) + 25) / 100) * 100;
}

double measured_template_scale(const FlightFrame& f, const Camera& camera, double metres_per_pixel) {
    // A barometer far off (or a reading near the ground) must not give a non-positive scale.
    return template_scale(camera, std::max(f.baro_altitude_m, 0.1 * f.truth.altitude_m), metres_per_pixel);
}

Pose FlightFrame::truth_pose() const {
    return {static_cast<float>(truth.map_x), static_cast<float>(truth.map_y), static_cast<float>(truth.yaw_rad),
            static_cast<float>(template_scale)};
}

FlightSimulator::FlightSimulator(const Map& map, const FlightConfig& config)
    : map_(map),
      config_(config),
      trajectory_(make_trajectory(map, config)),
      frame_count_(config.frames ? config.frames : config.scenario.frame_count()),
      odometry_(odometry_config(config)),
      magnetometer_([&] {
          MagnetometerConfig m = config.magnetometer;
          m.seed ^= detail::mix64(config.seed + 1);
          return m;
      }()),
      barometer_(BarometerConfig{config.scenario.realism.baro_noise_m, config.scenario.realism.baro_bias_walk_m_per_sqrt_s,
                                 detail::mix64(config.seed + 2)}),
      conditions_(config.scenario.realism, config.scenario.altitude_m, trajectory_.at(0).heading_rad, config.seed),
      profile_(config.scenario) {
    previous_ = trajectory_.at(0);
    previous_altitude_m_ = altitude_m(0);
    start_x_m_ = previous_.x_m, start_y_m_ = previous_.y_m;
}

double FlightSimulator::altitude_m(double t) const {
    return profile_.altitude_m(t) + (conditions_.altitude_m(t) - config_.scenario.altitude_m);
}

bool FlightSimulator::next(FlightFrame& f) {
    if (next_index_ >= frame_count_) return false;
    const std::size_t i = next_index_++;
    const double dt = 1.0 / config_.scenario.fps, t = i * dt;
    const TrajectoryState st = trajectory_.at(t);
    const double mpp = map_.metres_per_pixel, alt = altitude_m(t);

    f.index = i;
    f.time_s = t;
    f.truth.map_x = st.x_m / mpp;
    f.truth.map_y = st.y_m / mpp;
    f.truth.course_rad = wrap_angle(st.heading_rad);
    f.truth.yaw_rad = wrap_angle(st.heading_rad + conditions_.heading_offset_rad(t, st.heading_rad));
    f.truth.altitude_m = alt;
    // Unstabilised camera: slow, smooth wobble (two sines with seeded phases), not white noise.
    if (config_.camera_roll_pitch_sd_deg > 0) {
        const std::uint64_t h = detail::hash(config_.seed, 77);
        const double sd = config_.camera_roll_pitch_sd_deg * kDeg * std::sqrt(2.0);
        f.truth.roll_rad = sd * std::sin(2 * kPi * 0.31 * t + 2 * kPi * detail::unit(h, 0));
        f.truth.pitch_rad = sd * std::sin(2 * kPi * 0.23 * t + 2 * kPi * detail::unit(h, 1));
    } else {
        f.truth.roll_rad = f.truth.pitch_rad = 0;
    }
    f.position_m = {st.x_m - start_x_m_, -(st.y_m - start_y_m_), alt};
    f.geo = map_pixel_to_latlon(map_, f.truth.map_x, f.truth.map_y);
    f.template_scale = template_scale(config_.camera, alt, mpp);
    if (i == 0) {
        f.odometry_m = odometry_.estimate();
    } else {
        const Vec3 delta{st.x_m - previous_.x_m, -(st.y_m - previous_.y_m), alt - previous_altitude_m_};
        f.odometry_m = odometry_.step(delta, dt, st.yaw_rate_rad_s);
    }
    f.odometry_m.z += altitude_m(0);  // odometry is initialised with the first height, then drifts
    f.odometry_yaw_rad = wrap_angle(f.truth.yaw_rad + odometry_.heading_error_rad());  // its track is turned by the same error
    f.magnetometer_heading_rad = magnetometer_.read(f.truth.yaw_rad);
    f.baro_altitude_m = barometer_.read(alt, i == 0 ? 0 : dt);
    previous_ = st;
    previous_altitude_m_ = alt;

    if (config_.render_images) {
        RenderOptions r = config_.render;
        r.noise_seed = detail::hash(config_.seed ^ r.noise_seed, 78, static_cast<std::int64_t>(i)) | 1;
        const CameraPose pose{f.truth.map_x, f.truth.map_y, alt, f.truth.yaw_rad, f.truth.roll_rad, f.truth.pitch_rad};
        f.image = render_frame(map_, config_.camera, pose, r);
    } else {
        f.image = {};
    }
    return true;
}

}  // namespace trn::sim
