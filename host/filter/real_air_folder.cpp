#include "trn/filter/real_air_folder.hpp"

#include <cmath>

#include "trn/error.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/camera.hpp"
#include "trn/detail/angles.hpp"

namespace trn::reg {

void write_real_air_folder(const std::string& folder, const std::vector<PoseRow>& rows, const std::vector<GrayImage>& frames,
                           const RealAirOptions& o) {
    if (rows.empty() || rows.size() != frames.size()) throw Error("AIR folder " + folder + ": need one frame per pose");
    if (!(o.metres_per_pixel > 0) || !(o.fps > 0)) throw Error("AIR folder " + folder + ": metres per pixel and fps must be positive");
    sim::FlightInfo info;
    info.scenario = "real flight, truth from trnkit register";
    info.metres_per_pixel = o.metres_per_pixel;
    info.camera = {frames[0].width, frames[0].height, o.hfov_deg};
    info.camera.validate();
    info.fps = o.fps;
    info.frames = rows.size();
    info.seed = o.odometry.seed;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const Pose& p = rows[k].pose;
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw) && p.scale > 0) || frames[k].width < 2)
            throw Error("AIR folder " + folder + ": " + rows[k].frame + ": pose or frame unusable");
        try {
            sim::Camera{frames[k].width, frames[k].height, o.hfov_deg}.validate();  // each frame is its own camera size
        } catch (const Error& e) {
            throw Error("AIR folder " + folder + ": " + rows[k].frame + ": " + e.what());
        }
    }

    sim::OdometrySimulator odometry(o.odometry);
    sim::Magnetometer magnetometer(o.magnetometer);
    sim::AirWriter writer(folder);
    const double dt = 1 / o.fps, mpp = o.metres_per_pixel;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const Pose& p = rows[k].pose;
        // The altitude that gives this frame's found scale with its own focal length in pixels.
        const sim::Camera own{frames[k].width, frames[k].height, o.hfov_deg};

        sim::AirRecord r;
        r.filename = rows[k].frame;
        r.relative_altitude_m = p.scale * own.focal_px() * mpp;  // inverse of sim::template_scale
        r.pose_m = {(p.x - rows[0].pose.x) * mpp, -(p.y - rows[0].pose.y) * mpp, 0};  // east, north (map y is south)
        r.orientation = sim::attitude_quaternion(p.yaw);
        r.imu = sim::attitude_quaternion(magnetometer.read(p.yaw));
        r.map_x = p.x;
        r.map_y = p.y;
        if (k > 0) {
            const Pose& q = rows[k - 1].pose;
            const sim::Vec3 delta{(p.x - q.x) * mpp, -(p.y - q.y) * mpp, 0};
            odometry.step(delta, dt, wrap_angle(p.yaw - q.yaw) / dt);
        }
        r.svo_m = odometry.estimate();
        writer.write(r, frames[k].view());
    }
    writer.close();
    sim::write_flight_info(folder + "/flight.json", info);
}

}  // namespace trn::reg
