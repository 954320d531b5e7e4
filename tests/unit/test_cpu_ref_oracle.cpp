// cpu-ref is the oracle for every backend, so it is itself checked against independent code:
// OpenCV's warpAffine (float image, positions on its exact 1/32-pixel grid) + matchTemplate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "../common/test_images.hpp"
#include "trn/registry.hpp"

namespace trn {
namespace {

struct Expected {
    double ncc, cc, ssd;
};

// The patch the pose sees, taken with OpenCV, and the three measures computed by OpenCV.
Expected opencv_scores(const cv::Mat& map, const cv::Mat& templ, const Pose& p) {
    const double cx = (templ.cols - 1) / 2.0, cy = (templ.rows - 1) / 2.0;
    const double c = std::cos(p.yaw) * p.scale, s = std::sin(p.yaw) * p.scale;
    // dst (u, v) -> src: (x, y) + [c -s; s c] (u - cx, v - cy)
    const cv::Matx23d m(c, -s, p.x - c * cx + s * cy, s, c, p.y - s * cx - c * cy);
    cv::Mat mapf, patch, templf;
    map.convertTo(mapf, CV_32F);
    templ.convertTo(templf, CV_32F);
    cv::warpAffine(mapf, patch, m, templ.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
    cv::Mat r;
    cv::matchTemplate(patch, templf, r, cv::TM_CCOEFF_NORMED);
    const double ncc = r.at<float>(0, 0);
    cv::matchTemplate(patch, templf, r, cv::TM_CCORR_NORMED);
    const double cc = r.at<float>(0, 0);
    const double sq = cv::norm(patch, templf, cv::NORM_L2SQR);
    const double ssd = 1.0 - sq / std::sqrt(patch.dot(patch) * templf.dot(templf));
    return {ncc, cc, ssd};
}

TEST(CpuRefOracle, MatchesOpenCvOnExactGridPoses) {
    const auto map = test::textured_image(300, 240, 3), templ = test::textured_image(41, 30, 4);
    const cv::Mat map_mat = map.mat(), templ_mat = templ.mat();
    auto ref = default_registry().create("cpu-ref");
    const MapHandle h = ref->upload_map(map.view());
    const float pi = std::numbers::pi_v<float>;
    // Positions on multiples of 1/32 px with yaw 0 or a multiple of 90 degrees are exact in both.
    const std::vector<Pose> poses = {{150, 120, 0, 1},       {100.5f, 90.25f, 0, 1}, {77.03125f, 130.5f, 0, 1},
                                     {150, 120, pi / 2, 1},  {160.5f, 100, pi, 1},   {120, 140.75f, -pi / 2, 1},
                                     {150, 120, 0, 2},       {150, 120, 0, 0.5f}};
    std::vector<ParticleScore> out(poses.size());
    ref->score(h, templ.view(), poses, {}, out);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const Expected e = opencv_scores(map_mat, templ_mat, poses[i]);
        SCOPED_TRACE("pose " + std::to_string(i));
        ASSERT_TRUE(out[i].valid());
        EXPECT_EQ(out[i].valid_samples, 41u * 30u);
        // OpenCV's float sums and sin/cos(pi/2) ~ 1e-8 off grid: agreement to a few 1e-5.
        EXPECT_NEAR(out[i].ncc, e.ncc, 5e-5);
        EXPECT_NEAR(out[i].cc, e.cc, 5e-5);
        EXPECT_NEAR(out[i].ssd, e.ssd, 5e-5);
    }
    // The measures must actually discriminate: the first pose's template is unrelated noise.
    EXPECT_LT(std::fabs(out[0].ncc), 0.5f);
}

TEST(CpuRefOracle, PerfectMatchAndContrastInvariance) {
    const auto map = test::textured_image(200, 200, 9);
    auto ref = default_registry().create("cpu-ref");
    const MapHandle h = ref->upload_map(map.view());
    // Template = crop at (60, 70) scaled by 0.5 and offset by 20: NCC 1, CC and SSD below 1.
    const int w = 32, h2 = 24;
    std::vector<float> t(w * h2);
    for (int v = 0; v < h2; ++v)
        for (int u = 0; u < w; ++u) t[v * w + u] = 0.5f * map.view().at(60 + u, 70 + v) + 20.0f;
    const Pose p{60 + (w - 1) / 2.0f, 70 + (h2 - 1) / 2.0f, 0, 1};
    ParticleScore s;
    ref->score(h, FloatView{t.data(), w, h2, w}, std::span(&p, 1), {}, std::span(&s, 1));
    EXPECT_NEAR(s.ncc, 1.0f, 1e-6f);
    EXPECT_LT(s.ssd, 0.99f);
}

TEST(CpuRefOracle, YawTurnsTemplateClockwiseOnScreen) {
    // A template whose right half is bright matches, at yaw +90 degrees, a map whose lower half is
    // bright: positive yaw turns the template clockwise in image coordinates (y down).
    std::vector<std::uint8_t> map(100 * 100), templ(20 * 20);
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) map[y * 100 + x] = y >= 50 ? 200 : 30;
    for (int v = 0; v < 20; ++v)
        for (int u = 0; u < 20; ++u) templ[v * 20 + u] = u >= 10 ? 200 : 30;
    auto ref = default_registry().create("cpu-ref");
    const MapHandle h = ref->upload_map(GrayView{map.data(), 100, 100, 100});
    const std::vector<Pose> poses = {{50, 49.5f, std::numbers::pi_v<float> / 2, 1}, {50, 49.5f, -std::numbers::pi_v<float> / 2, 1}};
    std::vector<ParticleScore> out(2);
    ref->score(h, GrayView{templ.data(), 20, 20, 20}, poses, {}, out);
    EXPECT_GT(out[0].ncc, 0.99f);
    EXPECT_LT(out[1].ncc, -0.99f);
}

}  // namespace
}  // namespace trn
