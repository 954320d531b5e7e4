// Frames rendered by the simulator must score high at their true pose on the map they came from
// (and on an aged map), with a clear peak against poses 30 m away: the whole point of the tool.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sim_test_maps.hpp"
#include "trn/registry.hpp"
#include "trn/sim/camera.hpp"
#include "trn/sim/map_ageing.hpp"
#include "trn/sim/render.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

struct PeakResult {
    float truth = 0;
    float best_other = -1;
};

// NCC of the frame at its truth pose and at 8 poses `offset_m` away on `scoring_map`.
PeakResult score_peak(const Map& scoring_map, const GrayImage& frame, const Camera& cam, const CameraPose& pose,
                      double offset_m) {
    auto backend = default_registry().create("cpu");
    const MapHandle handle = backend->upload_map(scoring_map.image.view());
    const float scale = static_cast<float>(template_scale(cam, pose.altitude_m, scoring_map.metres_per_pixel));
    std::vector<Pose> poses{{float(pose.map_x), float(pose.map_y), float(pose.yaw_rad), scale}};
    const double d = offset_m / scoring_map.metres_per_pixel;
    for (int k = 0; k < 8; ++k) {
        const double a = k * kPi / 4;
        poses.push_back({float(pose.map_x + d * std::cos(a)), float(pose.map_y + d * std::sin(a)), float(pose.yaw_rad), scale});
    }
    std::vector<ParticleScore> scores(poses.size());
    backend->score(handle, frame.view(), poses, ScoreOptions{}, scores);
    PeakResult r;
    EXPECT_TRUE(scores[0].valid()) << "flags " << scores[0].flags;
    r.truth = scores[0].ncc;
    for (std::size_t i = 1; i < scores.size(); ++i) r.best_other = std::max(r.best_other, scores[i].ncc);
    std::printf("  ncc at truth %.3f, best of 8 poses %.0f m away %.3f\n", r.truth, offset_m, r.best_other);
    return r;
}

TEST(RenderScore, FrameScoresHighAtTruthWithClearPeakUrban) {
    const Map& map = testing::urban_map();
    const Camera cam;
    for (double yaw : {0.0, 0.7, -2.2}) {
        const CameraPose pose{320, 300, 200, yaw, 0, 0};
        const GrayImage frame = render_frame(map, cam, pose);
        const PeakResult r = score_peak(map, frame, cam, pose, 30);
        EXPECT_GT(r.truth, 0.9) << "yaw " << yaw;
        EXPECT_GT(r.truth - r.best_other, 0.2) << "yaw " << yaw << ": truth " << r.truth << " vs 30 m away " << r.best_other;
    }
}

TEST(RenderScore, FrameScoresHighAtTruthForest300m) {
    const Map& map = testing::forest_map();
    const Camera cam;
    const CameraPose pose{320, 330, 300, 1.3, 0, 0};
    const GrayImage frame = render_frame(map, cam, pose);
    const PeakResult r = score_peak(map, frame, cam, pose, 30);
    EXPECT_GT(r.truth, 0.9);
    EXPECT_GT(r.truth - r.best_other, 0.2) << "truth " << r.truth << " vs 30 m away " << r.best_other;
}

TEST(RenderScore, MapFinerThanCameraStillScoresHigh) {
    // Map finer than the camera (0.25 m/px at 300 m: ~2.2 map px per camera px).
    ProceduralMapOptions o = testing::small_map_options(TerrainStyle::Urban);
    o.metres_per_pixel = 0.25;
    o.width_m = o.height_m = 500;
    const Map map = generate_procedural_map(o);
    const Camera cam{320, 240, 60};
    const CameraPose pose{1000, 1000, 300, 0.4, 0, 0};
    const GrayImage frame = render_frame(map, cam, pose);
    const PeakResult r = score_peak(map, frame, cam, pose, 30);
    EXPECT_GT(r.truth, 0.85);
    EXPECT_GT(r.truth - r.best_other, 0.2);
}

TEST(RenderScore, AgedProceduralMapStillCorrelatesAtTruth) {
    const Map& base = testing::urban_map();
    const Map aged = generate_procedural_map(testing::small_map_options(TerrainStyle::Urban, 2014));
    // The world changed: the maps differ noticeably ...
    std::size_t differing = 0;
    for (std::size_t i = 0; i < base.image.pixels.size(); ++i)
        differing += std::abs(int(base.image.pixels[i]) - int(aged.image.pixels[i])) > 20;
    EXPECT_GT(differing, base.image.pixels.size() / 20);
    // ... but a frame of 2014 still finds its place on the 2008 map.
    const Camera cam;
    const CameraPose pose{320, 300, 200, 0.3, 0, 0};
    const GrayImage frame = render_frame(aged, cam, pose);
    const PeakResult r = score_peak(base, frame, cam, pose, 30);
    EXPECT_GT(r.truth, 0.5);
    EXPECT_GT(r.truth - r.best_other, 0.1) << "truth " << r.truth << " vs 30 m away " << r.best_other;
}

TEST(RenderScore, ImageAgedMapStillCorrelatesAtTruth) {
    const Map& base = testing::forest_map();
    MapAgeingOptions ageing;
    ageing.years = 6;
    ageing.seed = 3;
    const Map aged = age_map(base, ageing);
    ASSERT_EQ(aged.image.width, base.image.width);
    const Camera cam;
    const CameraPose pose{300, 320, 200, -0.5, 0, 0};
    const GrayImage frame = render_frame(aged, cam, pose);
    const PeakResult same = score_peak(aged, frame, cam, pose, 30);
    const PeakResult cross = score_peak(base, frame, cam, pose, 30);
    EXPECT_GT(same.truth, 0.9);
    EXPECT_LT(cross.truth, same.truth);  // ageing changed something the camera sees
    EXPECT_GT(cross.truth, 0.4);
    EXPECT_GT(cross.truth - cross.best_other, 0.1);
}

TEST(RenderScore, RealOrthophoto) {
    const auto path = testing::real_orthophoto();
    if (!path) GTEST_SKIP() << "TRN_SHARED_DATA/orthophoto.png not present; real-map rendering not tested";
    const Map map = load_map(*path, 0.5);
    const Camera cam;
    const CameraPose pose{map.image.width / 2.0, map.image.height / 2.0, 200, 0.9, 0, 0};
    const GrayImage frame = render_frame(map, cam, pose);
    const PeakResult r = score_peak(map, frame, cam, pose, 30);
    EXPECT_GT(r.truth, 0.9);
    EXPECT_GT(r.truth - r.best_other, 0.2) << "truth " << r.truth << " vs 30 m away " << r.best_other;
}

TEST(Camera, TemplateScaleAndLevelHomographyMatchTheScoringConvention) {
    const Camera cam;
    EXPECT_NEAR(cam.focal_px(), 320 / std::tan(kPi / 6), 1e-9);
    const double s = template_scale(cam, 200, 0.5);
    EXPECT_NEAR(s, 200 / (cam.focal_px() * 0.5), 1e-12);
    const CameraPose pose{100, 200, 200, 0.6, 0, 0};
    const auto h = camera_to_map_homography(cam, pose, 0.5);
    const double cx = 319.5, cy = 239.5;
    for (double u : {0.0, 100.0, 639.0})
        for (double v : {0.0, 479.0}) {
            const double w = h[6] * u + h[7] * v + h[8];
            const double x = (h[0] * u + h[1] * v + h[2]) / w, y = (h[3] * u + h[4] * v + h[5]) / w;
            const double c = std::cos(0.6), sn = std::sin(0.6);
            EXPECT_NEAR(x, 100 + s * (c * (u - cx) - sn * (v - cy)), 1e-6);
            EXPECT_NEAR(y, 200 + s * (sn * (u - cx) + c * (v - cy)), 1e-6);
        }
    EXPECT_THROW(template_scale(cam, -1, 1), Error);
    EXPECT_THROW(template_scale(Camera{640, 480, 0}, 100, 1), Error);
}

TEST(Camera, PitchAndRollShiftTheView) {
    const Camera cam;
    auto centre = [&](double roll, double pitch) {
        const auto h = camera_to_map_homography(cam, {500, 500, 200, 0, roll, pitch}, 1.0);
        const double w = h[6] * 319.5 + h[7] * 239.5 + h[8];
        return std::pair{(h[0] * 319.5 + h[1] * 239.5 + h[2]) / w, (h[3] * 319.5 + h[4] * 239.5 + h[5]) / w};
    };
    const double t = 200 * std::tan(0.05);
    EXPECT_NEAR(centre(0, 0.05).second, 500 - t, 1e-6);  // nose up at heading north: view moves north
    EXPECT_NEAR(centre(0.05, 0).first, 500 - t, 1e-6);   // right wing down: view moves left (west)
}

double stddev(const GrayImage& g) {
    double sum = 0, sum2 = 0;
    for (auto p : g.pixels) sum += p, sum2 += double(p) * p;
    const double n = double(g.pixels.size());
    return std::sqrt(sum2 / n - (sum / n) * (sum / n));
}

TEST(Render, AntiAliasingRemovesDetailFinerThanTheCamera) {
    // Stripes of 2 map pixels viewed 4 map pixels per camera pixel: a correctly filtered frame is
    // almost flat grey; point sampling would show strong false patterns (aliasing).
    Map stripes;
    stripes.image = {1200, 1200, std::vector<std::uint8_t>(1200 * 1200)};
    for (int y = 0; y < 1200; ++y)
        for (int x = 0; x < 1200; ++x) stripes.image.pixels[y * 1200 + x] = ((x + y) / 1) % 2 ? 200 : 50;
    const Camera cam{200, 150, 60};
    const double alt = 4 * cam.focal_px();  // scale 4 at 1 m/px
    RenderOptions opt;
    opt.noise_sigma = 0;
    const CameraPose pose{600, 600, alt, 0.3, 0, 0};
    const GrayImage filtered = render_frame(stripes, cam, pose, opt);
    opt.anti_alias = false;
    const GrayImage aliased = render_frame(stripes, cam, pose, opt);
    EXPECT_LT(stddev(filtered), 3.0);
    EXPECT_GT(stddev(aliased), 20.0);
}

TEST(Render, NoiseHasTheRequestedSigmaAndIsSeeded) {
    // A flat map makes the frame pure noise around the map's grey.
    Map flat;
    flat.image = {400, 400, std::vector<std::uint8_t>(400 * 400, 128)};
    const Camera cam{200, 150, 60};
    RenderOptions opt;
    opt.noise_seed = 5;
    const GrayImage a = render_frame(flat, cam, {200, 200, 100, 0, 0, 0}, opt);
    const GrayImage b = render_frame(flat, cam, {200, 200, 100, 0, 0, 0}, opt);
    EXPECT_EQ(a.pixels, b.pixels);
    double sum = 0, sum2 = 0;
    for (auto p : a.pixels) sum += p, sum2 += double(p) * p;
    const double n = double(a.pixels.size()), mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 128, 0.2);
    EXPECT_NEAR(sd, 0.02 * 255, 0.25);
}

TEST(Render, OutsideTheMapIsBlackAndBadInputThrows) {
    const Map& map = testing::urban_map();
    const Camera cam{64, 48, 60};
    const GrayImage f = render_frame(map, cam, {-500, -500, 100, 0, 0, 0}, {0.0, true, 1});
    EXPECT_TRUE(std::all_of(f.pixels.begin(), f.pixels.end(), [](std::uint8_t p) { return p == 0; }));
    EXPECT_THROW(render_frame(map, cam, {100, 100, 0, 0, 0, 0}), Error);
    EXPECT_THROW(render_frame(map, cam, {100, 100, 100, 0, 1.6, 0}), Error);
}

}  // namespace
}  // namespace trn::sim
