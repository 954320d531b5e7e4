#include "trn/filter/nadir_warp.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "trn/error.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/camera.hpp"
#include "trn/detail/angles.hpp"

namespace trn::filter {
namespace {

Eigen::Matrix3d matrix(const std::array<double, 9>& h) {
    Eigen::Matrix3d m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m(i, j) = h[i * 3 + j];
    return m;
}

// True when level pixel (u, v) maps (through m, level -> tilted) inside the tilted frame.
bool inside(const Eigen::Matrix3d& m, double u, double v, int width, int height) {
    const Eigen::Vector3d p = m * Eigen::Vector3d(u, v, 1);
    if (!(p.z() > 0)) return false;
    const double x = p.x() / p.z(), y = p.y() / p.z(), eps = 1e-6;  // rounding of the matrix product
    return x >= -eps && x <= width - 1 + eps && y >= -eps && y <= height - 1 + eps;
}

}  // namespace

NadirFrame warp_to_nadir(GrayView frame, double hfov_deg, double roll_rad, double pitch_rad) {
    if (frame.empty()) throw Error("warp_to_nadir: empty frame");
    const sim::Camera camera{frame.width, frame.height, hfov_deg};
    // Both homographies at one arbitrary place (the product does not depend on it): level pixel ->
    // ground -> tilted pixel.
    const sim::CameraPose level{0, 0, 100, 0, 0, 0}, tilted{0, 0, 100, 0, roll_rad, pitch_rad};
    const Eigen::Matrix3d level_to_tilted =
        matrix(sim::camera_to_map_homography(camera, tilted, 1)).inverse() * matrix(sim::camera_to_map_homography(camera, level, 1));

    // Largest centred rectangle (the frame's aspect) inside the tilted frame's footprint: the
    // footprint is convex, so the four corners decide.
    const double cx = (frame.width - 1) / 2.0, cy = (frame.height - 1) / 2.0;
    auto fits = [&](double s) {
        const double hx = s * cx, hy = s * cy;
        return inside(level_to_tilted, cx - hx, cy - hy, frame.width, frame.height) &&
               inside(level_to_tilted, cx + hx, cy - hy, frame.width, frame.height) &&
               inside(level_to_tilted, cx - hx, cy + hy, frame.width, frame.height) &&
               inside(level_to_tilted, cx + hx, cy + hy, frame.width, frame.height);
    };
    double lo = 0, hi = 1;
    if (fits(1)) lo = 1;
    for (int i = 0; i < 40 && hi - lo > 1e-6; ++i) (fits((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
    // Spans at most s * (full - 1) pixels, centred: its centre is the frame's (cx, cy) exactly.
    auto crop_size = [](int full, double s) { return static_cast<int>(std::floor(s * (full - 1))) + 1; };
    const int width = crop_size(frame.width, lo), height = crop_size(frame.height, lo);
    if (width < 8 || height < 8)
        throw Error("warp_to_nadir: roll " + std::to_string(roll_rad * 180 / kPi) + " deg, pitch " +
                    std::to_string(pitch_rad * 180 / kPi) + " deg leave no usable level view");

    // Output pixel (i, j) is level pixel (i + ox, j + oy).
    const double ox = (frame.width - width) / 2.0, oy = (frame.height - height) / 2.0;
    Eigen::Matrix3d shift;
    shift << 1, 0, ox, 0, 1, oy, 0, 0, 1;
    const Eigen::Matrix3d out_to_tilted = level_to_tilted * shift;
    cv::Mat m(3, 3, CV_64F);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.at<double>(i, j) = out_to_tilted(i, j);

    NadirFrame out;
    out.image.width = width, out.image.height = height;
    out.image.pixels.resize(std::size_t(width) * height);
    const cv::Mat src(frame.height, frame.width, CV_8UC1, const_cast<std::uint8_t*>(frame.data), std::size_t(frame.stride));
    cv::Mat dst(height, width, CV_8UC1, out.image.pixels.data());
    cv::warpPerspective(src, dst, m, dst.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
    out.kept_fraction = double(width) / frame.width;
    return out;
}

double tilt_deg(double roll_rad, double pitch_rad) { return sim::tilt_from_nadir(roll_rad, pitch_rad) * 180 / kPi; }

LevelledFrame level_frame(GrayView frame, double hfov_deg, double roll_rad, double pitch_rad, double max_tilt_deg) {
    LevelledFrame l;
    l.tilt_deg = tilt_deg(roll_rad, pitch_rad);
    if (l.tilt_deg > max_tilt_deg) {  // never scored at a wrong place and scale
        char why[96];
        std::snprintf(why, sizeof why, "tilted %.6g deg from nadir, more than %.6g", l.tilt_deg, max_tilt_deg);
        l.too_oblique = true, l.error = why;
        return l;
    }
    if (l.tilt_deg <= kLevelTiltDeg) return l;
    if (!(hfov_deg > 0 && hfov_deg < 180))
        throw Error("level_frame: a frame tilted " + std::to_string(l.tilt_deg) + " deg needs its horizontal field of view (hfov_deg), got " +
                    std::to_string(hfov_deg));
    try {
        l.image = warp_to_nadir(frame, hfov_deg, roll_rad, pitch_rad).image;
    } catch (const Error& e) {  // no level view left (a generous max_tilt_deg): too oblique after all
        l.too_oblique = true, l.error = e.what();
    }
    return l;
}

}  // namespace trn::filter
