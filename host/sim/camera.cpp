#include "trn/sim/camera.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "trn/error.hpp"
#include "trn/limits.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {

double Camera::focal_px() const { return 0.5 * width / std::tan(0.5 * hfov_deg * kPi / 180.0); }

void Camera::validate() const {
    if (width < 2 || height < 2)
        throw Error("camera: size " + std::to_string(width) + "x" + std::to_string(height) + " must be at least 2x2");
    // Frames are rendered at this size and scored (downscaled) as templates.
    limits::check_image("camera: frame", width, height, limits::kMaxTemplatePixels, limits::kLoadBytesPerPixel);
    if (!(hfov_deg > 1 && hfov_deg < 170))
        throw Error("camera: field of view " + std::to_string(hfov_deg) + " degrees must be in (1, 170)");
}

double template_scale(const Camera& camera, double altitude_m, double metres_per_pixel) {
    camera.validate();
    if (!(altitude_m > 0)) throw Error("template_scale: altitude " + std::to_string(altitude_m) + " m must be > 0");
    if (!(metres_per_pixel > 0))
        throw Error("template_scale: map resolution " + std::to_string(metres_per_pixel) + " m/px must be > 0");
    return altitude_m / (camera.focal_px() * metres_per_pixel);
}

std::array<double, 9> camera_to_map_homography(const Camera& camera, const CameraPose& pose, double metres_per_pixel) {
    camera.validate();
    // World frame in map pixels: X east, Y south, Z down (right-handed); the level camera's
    // x/y/z axes are the world's, so (u - cx, v - cy, f) points at the ground below.
    const double f = camera.focal_px(), cx = (camera.width - 1) / 2.0, cy = (camera.height - 1) / 2.0;
    Eigen::Matrix3d k_inv;
    k_inv << 1 / f, 0, -cx / f, 0, 1 / f, -cy / f, 0, 0, 1;
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pose.pitch_rad, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(-pose.roll_rad, Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
    const double h = pose.altitude_m / metres_per_pixel;  // camera height in map pixels
    Eigen::Matrix3d ground;  // ray direction d -> ground point (x + h dx/dz, y + h dy/dz)
    ground << h, 0, pose.map_x, 0, h, pose.map_y, 0, 0, 1;
    const Eigen::Matrix3d hm = ground * r * k_inv;
    std::array<double, 9> out{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[i * 3 + j] = hm(i, j) / hm(2, 2);
    return out;
}

}  // namespace trn::sim
