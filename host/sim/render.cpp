#include "trn/sim/render.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "trn/error.hpp"

namespace trn::sim {

GrayImage render_frame(const Map& map, const Camera& camera, const CameraPose& pose, const RenderOptions& options) {
    camera.validate();
    if (map.image.width < 2 || map.image.height < 2) throw Error("render_frame: the map is empty");
    if (!(pose.altitude_m > 0)) throw Error("render_frame: altitude " + std::to_string(pose.altitude_m) + " m must be > 0");
    if (!(options.noise_sigma >= 0)) throw Error("render_frame: noise sigma must be >= 0");

    const std::array<double, 9> hm = camera_to_map_homography(camera, pose, map.metres_per_pixel);
    // Footprint of the frame on the map, to crop and filter only what the camera sees.
    double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
    for (double u : {0.0, camera.width - 1.0})
        for (double v : {0.0, camera.height - 1.0}) {
            const double w = hm[6] * u + hm[7] * v + hm[8];
            if (!(w > 1e-9)) throw Error("render_frame: the camera sees the horizon (roll/pitch too large)");
            const double x = (hm[0] * u + hm[1] * v + hm[2]) / w, y = (hm[3] * u + hm[4] * v + hm[5]) / w;
            min_x = std::min(min_x, x), max_x = std::max(max_x, x), min_y = std::min(min_y, y), max_y = std::max(max_y, y);
        }
    // Map pixels per camera pixel, measured along the frame's edges (the local sampling step).
    const double step = std::hypot(max_x - min_x, max_y - min_y) / std::hypot(camera.width - 1.0, camera.height - 1.0);
    const int margin = 4 + static_cast<int>(std::ceil(3 * step));
    const int x0 = std::clamp(static_cast<int>(std::floor(min_x)) - margin, 0, map.image.width - 1);
    const int y0 = std::clamp(static_cast<int>(std::floor(min_y)) - margin, 0, map.image.height - 1);
    const int x1 = std::clamp(static_cast<int>(std::ceil(max_x)) + margin, 0, map.image.width - 1);
    const int y1 = std::clamp(static_cast<int>(std::ceil(max_y)) + margin, 0, map.image.height - 1);

    cv::Mat out(camera.height, camera.width, CV_32F, cv::Scalar(0));
    if (x1 > x0 && y1 > y0) {
        const cv::Mat whole(map.image.height, map.image.width, CV_8UC1, const_cast<std::uint8_t*>(map.image.pixels.data()));
        cv::Mat crop;
        whole(cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1)).convertTo(crop, CV_32F);
        // Low-pass before resampling when the map is finer than the camera: a Gaussian whose
        // width grows with the step keeps the frame free of aliasing (bilinear alone would not).
        if (options.anti_alias && step > 1.0) {
            const double sigma = 0.5 * std::sqrt(step * step - 1.0);
            cv::GaussianBlur(crop, crop, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT_101);
        }
        // Same homography, but into the crop's coordinates.
        const cv::Matx33d h(hm[0] - x0 * hm[6], hm[1] - x0 * hm[7], hm[2] - x0 * hm[8],  //
                            hm[3] - y0 * hm[6], hm[4] - y0 * hm[7], hm[5] - y0 * hm[8],  //
                            hm[6], hm[7], hm[8]);
        cv::warpPerspective(crop, out, h, out.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                            cv::Scalar(0));
    }
    if (options.noise_sigma > 0) {
        cv::Mat noise(out.size(), CV_32F);
        cv::RNG rng(options.noise_seed ? options.noise_seed : 1);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, options.noise_sigma * 255.0);
        out += noise;
    }
    GrayImage frame{camera.width, camera.height, std::vector<std::uint8_t>(std::size_t(camera.width) * camera.height)};
    cv::Mat dst(camera.height, camera.width, CV_8UC1, frame.pixels.data());
    out.convertTo(dst, CV_8U);  // rounds and saturates
    return frame;
}

}  // namespace trn::sim
