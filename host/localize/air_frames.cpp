#include "trn/localize/air_frames.hpp"

#include "trn/error.hpp"

namespace trn::localize {

OdometryIncrements::Step OdometryIncrements::next(double east_m, double north_m) {
    if (!std::isfinite(east_m) || !std::isfinite(north_m)) return {};
    if (!started_) e0_ = prev_e_ = east_m, n0_ = prev_n_ = north_m, started_ = true;
    const Step step{east_m - prev_e_, north_m - prev_n_};
    prev_e_ = east_m, prev_n_ = north_m;
    return step;
}

Observation AirFrame::observation() const {
    Observation o;
    if (!image.pixels.empty()) o.frame = image.view();
    o.altitude_agl_m = altitude_agl_m;
    o.odometry_east_m = odometry_step.east_m, o.odometry_north_m = odometry_step.north_m;
    o.heading_rad = heading_rad;
    o.has_attitude = true, o.roll_rad = roll_rad, o.pitch_rad = pitch_rad;
    return o;
}

AirFrameReader::AirFrameReader(const std::string& folder) : reader_(folder) {}

std::string AirFrameReader::position() const { return reader_.folder() + "/metadata.csv:" + std::to_string(reader_.line()); }

bool AirFrameReader::next(AirFrame& f) {
    sim::AirRecord r;
    if (!reader_.next(r)) return false;
    f = {};
    f.row = row_++;
    f.filename = r.filename;
    f.altitude_agl_m = r.relative_altitude_m;
    f.heading_rad = sim::heading_from_quaternion(r.imu);
    const sim::RollPitch rp = sim::roll_pitch_from_quaternion(r.imu);
    f.roll_rad = rp.roll_rad, f.pitch_rad = rp.pitch_rad;
    f.odometry_east_m = r.svo_m.x, f.odometry_north_m = r.svo_m.y;
    f.odometry_step = odometry_.next(r.svo_m.x, r.svo_m.y);
    if (std::isfinite(r.map_x) && std::isfinite(r.map_y)) f.truth_x = r.map_x, f.truth_y = r.map_y;
    try {
        f.image = reader_.load_image(r);
    } catch (const Error& e) {
        f.image_error = e.what();
    }
    return true;
}

}  // namespace trn::localize
