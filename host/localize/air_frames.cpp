#include "trn/localize/air_frames.hpp"

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"

namespace trn::localize {

OdometryIncrements::Step OdometryIncrements::next(double east_m, double north_m) {
    if (!std::isfinite(east_m) || !std::isfinite(north_m)) return {};
    if (!started_) e0_ = prev_e_ = east_m, n0_ = prev_n_ = north_m, started_ = true;
    const Step step{east_m - prev_e_, north_m - prev_n_};
    prev_e_ = east_m, prev_n_ = north_m;
    return step;
}

CompasslessOdometry::Step CompasslessOdometry::next(const OdometryIncrements::Step& step, double yaw) {
    Step out;
    if (!std::isfinite(step.east_m) || !std::isfinite(step.north_m)) return out;  // lost: the next step spans the gap
    if (!started_) started_ = true, yaw_ = yaw, out.rotation_rad = 0;             // the start: no turn before it
    else if (std::isfinite(yaw_) && std::isfinite(yaw)) out.rotation_rad = wrap_angle(yaw - yaw_);
    if (std::isfinite(yaw_)) {  // forward = along the frame top, right = 90 degrees clockwise of it
        const double s = std::sin(yaw_), c = std::cos(yaw_);
        out.forward_m = step.east_m * s + step.north_m * c, out.right_m = step.east_m * c - step.north_m * s;
    } else {  // no yaw known: the step as it is
        out.forward_m = step.north_m, out.right_m = step.east_m;
    }
    if (std::isfinite(yaw)) yaw_ = yaw;
    return out;
}

Observation AirFrame::observation_without_compass() const {
    Observation o = observation();
    o.heading_rad = NAN;
    o.odometry_east_m = compassless_step.right_m, o.odometry_north_m = compassless_step.forward_m;
    o.odometry_yaw_rad = compassless_step.rotation_rad;
    return o;
}

Observation AirFrame::observation() const {
    Observation o;
    if (!image.pixels.empty()) o.frame = image.view();
    o.altitude_agl_m = altitude_agl_m;
    o.odometry_east_m = odometry_step.east_m, o.odometry_north_m = odometry_step.north_m;
    o.heading_rad = heading_rad;
    o.has_attitude = true, o.roll_rad = roll_rad, o.pitch_rad = pitch_rad;
    o.time_s = time_s;
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
    f.time_s = r.time_s;
    f.heading_rad = sim::heading_from_quaternion(r.imu);
    const sim::RollPitch rp = sim::roll_pitch_from_quaternion(r.imu);
    f.roll_rad = rp.roll_rad, f.pitch_rad = rp.pitch_rad;
    f.odometry_east_m = r.svo_m.x, f.odometry_north_m = r.svo_m.y;
    f.odometry_step = odometry_.next(r.svo_m.x, r.svo_m.y);
    f.compassless_step = compassless_.next(f.odometry_step, f.heading_rad);  // the folder's odometry yaw: its heading
    if (std::isfinite(r.map_x) && std::isfinite(r.map_y)) f.truth_x = r.map_x, f.truth_y = r.map_y;
    try {
        f.image = reader_.load_image(r);
    } catch (const Error& e) {
        f.image_error = e.what();
    }
    return true;
}

}  // namespace trn::localize
