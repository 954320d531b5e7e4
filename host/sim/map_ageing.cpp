// Ageing an arbitrary map image (see map_ageing.hpp). Works on a float copy with OpenCV.
#include "trn/sim/map_ageing.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "random.hpp"
#include "trn/error.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

// Smooth random field in [0, 1] with features of about `cell_px` pixels.
cv::Mat smooth_noise(cv::Size size, double cell_px, std::uint64_t& rng) {
    const int gw = std::max(2, static_cast<int>(size.width / cell_px) + 2), gh = std::max(2, static_cast<int>(size.height / cell_px) + 2);
    cv::Mat grid(gh, gw, CV_32F);
    for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x) grid.at<float>(y, x) = static_cast<float>(detail::uniform(rng));
    cv::Mat out;
    cv::resize(grid, out, size, 0, 0, cv::INTER_CUBIC);
    return out;
}

}  // namespace

Map age_map(const Map& map, const MapAgeingOptions& o) {
    if (map.image.width < 2 || map.image.height < 2) throw Error("age_map: the map is empty");
    if (!(o.years >= 0)) throw Error("age_map: years " + std::to_string(o.years) + " must be >= 0");
    const double strength = std::min(1.0, o.years / 8.0);
    std::uint64_t rng = detail::mix64(o.seed ^ 0xA9E1ull);
    const cv::Mat src(map.image.height, map.image.width, CV_8UC1, const_cast<std::uint8_t*>(map.image.pixels.data()));
    cv::Mat img;
    src.convertTo(img, CV_32F);
    const cv::Size size = img.size();
    const double px_per_m = 1.0 / map.metres_per_pixel;

    // Season and brightness: a tone curve (gamma), gain and offset.
    const double gamma = 1.0 + strength * (detail::uniform(rng) - 0.5) * 0.5;
    const double gain = 1.0 + strength * (detail::uniform(rng) - 0.5) * 0.3;
    const double offset = strength * (detail::uniform(rng) - 0.5) * 30;
    cv::Mat t;
    cv::pow(img / 255.0, gamma, t);
    img = t * (255.0 * gain) + offset;

    // Illumination / haze that varies over hundreds of metres.
    img = img.mul(1.0 + 0.15 * strength * (smooth_noise(size, 300 * px_per_m, rng) - 0.5));

    // Changed vegetation: in blobs covering the chosen share of the area the texture is replaced
    // by a smoothed, re-toned version plus new crop rows.
    const double share = std::min(0.6, o.vegetation_change_share_per_year * o.years);
    if (share > 0) {
        const cv::Mat blobs = smooth_noise(size, 150 * px_per_m, rng);
        std::vector<float> sorted(blobs.begin<float>(), blobs.end<float>());
        const std::size_t k = static_cast<std::size_t>((1.0 - share) * (sorted.size() - 1));
        std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
        const float level = sorted[k];
        cv::Mat smooth;
        cv::GaussianBlur(img, smooth, cv::Size(0, 0), 2.0 * px_per_m);
        const double angle = detail::uniform(rng) * kPi, period_px = std::max(2.6, 4.0 * px_per_m);
        const double tone = 0.75 + 0.5 * detail::uniform(rng);
        for (int y = 0; y < size.height; ++y) {
            float* row = img.ptr<float>(y);
            const float* b = blobs.ptr<float>(y);
            const float* s = smooth.ptr<float>(y);
            for (int x = 0; x < size.width; ++x) {
                // Soft edge over a few percent of the noise range.
                const double w = std::clamp((b[x] - level) / 0.02, 0.0, 1.0);
                if (w <= 0) continue;
                const double rows = 12 * std::sin(2 * kPi * (x * std::cos(angle) + y * std::sin(angle)) / period_px);
                row[x] = static_cast<float>((1 - w) * row[x] + w * (s[x] * tone + rows));
            }
        }
    }

    // Removed buildings: small patches smoothed into their surroundings. New buildings: roofs with
    // a cast shadow in a new sun direction (the old shadows stay: an image has no geometry).
    const double area_km2 = map.width_m() * map.height_m() / 1e6;
    const int count = static_cast<int>(std::lround(area_km2 * o.new_buildings_per_km2_per_year * o.years));
    cv::Mat blurred;
    cv::GaussianBlur(img, blurred, cv::Size(0, 0), 6.0 * px_per_m);
    const double sun = 2 * kPi * detail::uniform(rng), shadow_len = (4 + 6 * detail::uniform(rng)) * px_per_m;
    for (int i = 0; i < 2 * count; ++i) {
        const double cx = detail::uniform(rng) * size.width, cy = detail::uniform(rng) * size.height;
        const double w = o.building_size_m * px_per_m * (0.7 + 0.7 * detail::uniform(rng));
        const double h = o.building_size_m * px_per_m * (0.7 + 0.7 * detail::uniform(rng));
        const double ang = detail::uniform(rng) * 180;
        const cv::RotatedRect rect{cv::Point2f{float(cx), float(cy)}, cv::Size2f{float(w), float(h)}, float(ang)};
        cv::Point2f corners[4];
        rect.points(corners);
        std::vector<cv::Point> poly(4);
        for (int c = 0; c < 4; ++c) poly[c] = cv::Point(cvRound(corners[c].x), cvRound(corners[c].y));
        if (i % 2 == 1) {  // removed: take the smoothed surroundings
            cv::Mat mask = cv::Mat::zeros(size, CV_8U);
            cv::fillConvexPoly(mask, poly, 255);
            blurred.copyTo(img, mask);
            continue;
        }
        std::vector<cv::Point> shadow(4);
        const cv::Point2f off(float(std::cos(sun) * shadow_len), float(std::sin(sun) * shadow_len));
        for (int c = 0; c < 4; ++c) shadow[c] = cv::Point(cvRound(corners[c].x + off.x), cvRound(corners[c].y + off.y));
        const double roof = 80 + 120 * detail::uniform(rng);
        cv::fillConvexPoly(img, shadow, cv::Scalar(35));
        cv::fillConvexPoly(img, poly, cv::Scalar(roof));
    }

    Map out;
    out.metres_per_pixel = map.metres_per_pixel;
    out.origin = map.origin;
    out.image = {map.image.width, map.image.height, std::vector<std::uint8_t>(map.image.pixels.size())};
    cv::Mat dst(size, CV_8UC1, out.image.pixels.data());
    img.convertTo(dst, CV_8U);
    return out;
}

}  // namespace trn::sim
