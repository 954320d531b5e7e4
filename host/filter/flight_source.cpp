#include "trn/filter/flight_source.hpp"

#include <cmath>
#include <fstream>

#include "trn/error.hpp"
#include "trn/sim/render.hpp"

namespace trn::filter {

AirFlightSource::AirFlightSource(const std::string& folder, const sim::Camera& camera, double metres_per_pixel,
                                 double fps, std::size_t stride, std::size_t frames_hint)
    : reader_(folder), camera_(camera), mpp_(metres_per_pixel), fps_(fps), stride_(stride), hint_(frames_hint) {
    if (!(fps > 0)) throw Error("AirFlightSource: fps must be > 0");
    if (stride == 0) throw Error("AirFlightSource: stride must be >= 1");
    if (!(metres_per_pixel > 0)) throw Error("AirFlightSource: metres_per_pixel must be > 0");
    camera.validate();
}

bool AirFlightSource::next(FlightSample& s) {
    sim::AirRecord r;
    while (reader_.next(r)) {
        const std::size_t row = row_++;
        if (row % stride_) continue;
        s.frame_index = row;
        s.time_s = row / fps_;
        s.has_truth = std::isfinite(r.map_x) && std::isfinite(r.map_y);
        s.truth_x = r.map_x, s.truth_y = r.map_y;
        s.truth_yaw = sim::heading_from_quaternion(r.orientation);
        s.odometry_east_m = r.svo_m.x, s.odometry_north_m = r.svo_m.y;
        s.heading_rad = sim::heading_from_quaternion(r.imu);
        s.map_px_per_camera_px = sim::template_scale(camera_, r.relative_altitude_m, mpp_);
        s.image = {};
        s.image_error.clear();
        try {
            s.image = reader_.load_image(r);
        } catch (const Error& e) {
            s.image_error = e.what();  // counted by the filter as a missing frame
        }
        return true;
    }
    return false;
}

SimulatedFlightSource::SimulatedFlightSource(const sim::Map& world, const sim::FlightConfig& config, std::size_t stride)
    : world_(world),
      config_(config),
      simulator_(world, [&] {
          sim::FlightConfig c = config;
          c.render_images = false;  // rendered here, only for the frames the filter uses
          return c;
      }()),
      stride_(stride) {
    if (stride == 0) throw Error("SimulatedFlightSource: stride must be >= 1");
}

bool SimulatedFlightSource::next(FlightSample& s) {
    sim::FlightFrame f;
    while (simulator_.next(f)) {
        if (f.index % stride_) continue;
        s.frame_index = f.index;
        s.time_s = f.time_s;
        s.has_truth = true;
        s.truth_x = f.truth.map_x, s.truth_y = f.truth.map_y, s.truth_yaw = f.truth.yaw_rad;
        s.odometry_east_m = f.odometry_m.x, s.odometry_north_m = f.odometry_m.y;
        s.heading_rad = f.magnetometer_heading_rad;
        s.map_px_per_camera_px = sim::measured_template_scale(f, config_.camera, world_.metres_per_pixel);  // barometric, like a real flight
        sim::RenderOptions r = config_.render;
        r.noise_seed = ((config_.seed * 0x9E3779B97F4A7C15ull) ^ (r.noise_seed + 0x632BE59BD9B4E019ull * (f.index + 1))) | 1;
        const sim::CameraPose pose{f.truth.map_x, f.truth.map_y, f.truth.altitude_m, f.truth.yaw_rad, f.truth.roll_rad, f.truth.pitch_rad};
        s.image = sim::render_frame(world_, config_.camera, pose, r);
        s.image_error.clear();
        return true;
    }
    return false;
}

std::size_t count_air_rows(const std::string& folder) {
    std::ifstream in(folder + "/metadata.csv");
    if (!in) return 0;
    std::size_t lines = 0;
    std::string line;
    while (std::getline(in, line))
        if (!line.empty()) ++lines;
    return lines ? lines - 1 : 0;
}

}  // namespace trn::filter
