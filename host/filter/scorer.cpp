#include "trn/filter/scorer.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "trn/error.hpp"

namespace trn::filter {

GrayImage downscale_frame(GrayView frame, int width, double& factor) {
    if (frame.empty()) throw Error("downscale_frame: empty camera frame");
    GrayImage out;
    if (width <= 0 || width >= frame.width) {
        factor = 1.0;
        out.width = frame.width, out.height = frame.height;
        out.pixels.resize(std::size_t(frame.width) * frame.height);
        for (int y = 0; y < frame.height; ++y) std::copy_n(frame.row(y), frame.width, out.pixels.data() + std::size_t(y) * frame.width);
        return out;
    }
    factor = double(frame.width) / width;
    const int height = std::max(2, static_cast<int>(std::lround(frame.height / factor)));
    const cv::Mat src(frame.height, frame.width, CV_8UC1, const_cast<std::uint8_t*>(frame.data), std::size_t(frame.stride));
    out.width = width, out.height = height;
    out.pixels.resize(std::size_t(width) * height);
    cv::Mat dst(height, width, CV_8UC1, out.pixels.data());
    cv::resize(src, dst, dst.size(), 0, 0, cv::INTER_AREA);
    return out;
}

BackendScorer::BackendScorer(Backend& backend, GrayView map, const BackendScorerOptions& options, GrayView valid)
    : backend_(backend), map_width_(map.width), map_height_(map.height), map_(backend.upload_map(map, valid)), options_(options) {
    if (options.template_width != 0 && options.template_width < 8)
        throw Error("BackendScorer: template_width " + std::to_string(options.template_width) + " must be 0 or >= 8");
}

void BackendScorer::score(GrayView camera_frame, double map_px_per_camera_px, std::span<const Pose> poses,
                          std::span<ParticleScore> out, PhaseTimes* times) {
    if (!(map_px_per_camera_px > 0) || !std::isfinite(map_px_per_camera_px))
        throw Error("BackendScorer::score: map_px_per_camera_px must be > 0");
    double factor = 1.0;
    small_ = downscale_frame(camera_frame, options_.template_width, factor);
    // The downscaled frame keeps the same footprint: each template pixel covers `factor` camera pixels.
    const float scale = static_cast<float>(map_px_per_camera_px * factor);
    scaled_.assign(poses.begin(), poses.end());
    for (Pose& p : scaled_) p.scale = scale;
    ScoreOptions so;
    so.sampling = options_.sampling;
    so.min_valid_fraction = options_.min_valid_fraction;
    backend_.score(map_, small_.view(), scaled_, so, out, times);
}

}  // namespace trn::filter
