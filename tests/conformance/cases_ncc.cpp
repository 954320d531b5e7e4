// Batched scoring cases: sizes, sampling modes, strides, map edges, flat images, yaw/scale sweeps,
// large templates and maps, and the real orthophoto when it is present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>

#include "../common/test_images.hpp"
#include "cases.hpp"
#include "checks.hpp"
#include "trn/io/image_io.hpp"
#include "../common/shared_data.hpp"

namespace trn::conformance {
namespace {

using test::PaddedGray;
using test::textured_image;

void random_sizes(Backend& dut, Backend& ref) {
    for (std::uint32_t seed = 1; seed <= 8; ++seed) {
        std::mt19937 rng(seed);
        const int mw = std::uniform_int_distribution<int>(40, 400)(rng), mh = std::uniform_int_distribution<int>(40, 400)(rng);
        const int tw = std::uniform_int_distribution<int>(3, std::min(mw, 64))(rng);
        const int th = std::uniform_int_distribution<int>(3, std::min(mh, 64))(rng);
        const PaddedGray map = textured_image(mw, mh, seed);
        const PaddedGray templ = textured_image(tw, th, seed + 100);
        const auto poses = random_poses(rng, 97, mw, mh, 0.1f, 0.5f, 2.0f);
        SCOPED_TRACE("seed " + std::to_string(seed));
        score_and_compare(dut, ref, map.view(), templ.view(), poses, {});
    }
}

void sparse_random(Backend& dut, Backend& ref) {
    std::mt19937 rng(11);
    const PaddedGray map = textured_image(300, 260, 11), templ = textured_image(121, 91, 12);
    const auto poses = random_poses(rng, 128, 300, 260, 0.05f, 0.6f, 1.5f);
    for (double fraction : {0.1, 0.37, 1.0}) {
        SCOPED_TRACE("fraction " + std::to_string(fraction));
        ScoreOptions o;
        o.sampling = Sampling::random(fraction, 42);
        score_and_compare(dut, ref, map.view(), templ.view(), poses, o);
    }
}

void explicit_points(Backend& dut, Backend& ref) {
    std::mt19937 rng(13);
    const PaddedGray map = textured_image(200, 180, 13), templ = textured_image(40, 30, 14);
    std::vector<SamplePoint> pts = {{0, 0}, {39, 0}, {0, 29}, {39, 29}, {20, 15}};
    for (int k = 0; k < 60; ++k) pts.push_back({int(rng() % 40), int(rng() % 30)});  // duplicates allowed
    ScoreOptions o;
    o.sampling = Sampling::explicit_points(pts);
    score_and_compare(dut, ref, map.view(), templ.view(), random_poses(rng, 150, 200, 180, 0.05f, 0.5f, 2.5f), o);
}

void strided_rois(Backend& dut, Backend& ref) {
    std::mt19937 rng(17);
    // Map and templates are ROIs of larger buffers (stride > width), one template in float.
    const PaddedGray map = textured_image(257, 199, 17, 13), templ = textured_image(33, 27, 18, 5);
    std::vector<float> ftempl(std::size_t(27) * 40, -1e30f);  // stride 40, junk beyond the ROI
    for (int y = 0; y < 27; ++y)
        for (int x = 0; x < 33; ++x) ftempl[y * 40 + x] = templ.view().at(x, y) * 0.37f + 3.0f;
    const auto poses = random_poses(rng, 111, 257, 199, 0.1f, 0.7f, 1.8f);
    score_and_compare(dut, ref, map.view(), templ.view(), poses, {});
    score_and_compare(dut, ref, map.view(), FloatView{ftempl.data(), 33, 27, 40}, poses, {});
}

void map_edges(Backend& dut, Backend& ref) {
    const int mw = 150, mh = 120;
    const PaddedGray map = textured_image(mw, mh, 19), templ = textured_image(21, 16, 20);
    std::vector<Pose> poses;
    const float xs[] = {0.0f, 0.5f, 10.0f, 74.5f, float(mw - 11), float(mw - 1), float(mw - 1) + 1e-3f, float(mw), -10.0f, -30.0f, 200.0f};
    const float ys[] = {0.0f, 8.0f, 60.0f, float(mh - 8), float(mh - 1), float(mh) + 5.0f, -7.5f};
    for (float x : xs)
        for (float y : ys)
            for (float yaw : {0.0f, 0.5f, -2.0f}) poses.push_back({x, y, yaw, 1.0f});
    // Exactly on the last row/column at scale 1, yaw 0: samples land on integer map coordinates.
    poses.push_back({10.0f, float(mh - 1) - 7.5f, 0.0f, 1.0f});
    poses.push_back({float(mw - 1) - 10.0f, 7.5f, 0.0f, 1.0f});
    for (double min_valid : {0.9, 0.5, 0.0, 1.0}) {
        SCOPED_TRACE("min_valid_fraction " + std::to_string(min_valid));
        ScoreOptions o;
        o.min_valid_fraction = min_valid;
        const auto got = score_and_compare(dut, ref, map.view(), templ.view(), poses, o);
        if (min_valid == 0.9) {  // the case must exercise all three outcomes
            EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.valid(); }));
            EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.flags & kTooFewSamples; }));
            EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.valid_samples == 0; }));
        }
    }
}

// Long rows over every edge and corner, any yaw and scale: rows that enter or leave the map part
// way (the cpu backend samples only their run inside; AVX2 steps of 16 and 8 and a tail).
void map_edges_long_rows(Backend& dut, Backend& ref) {
    const int mw = 300, mh = 220;
    const PaddedGray map = textured_image(mw, mh, 29), templ = textured_image(131, 97, 30);
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> along(-20.0f, 320.0f), across(-60.0f, 60.0f), yaw(-3.14159f, 3.14159f), scale(0.6f, 1.6f);
    std::vector<Pose> poses;
    for (int i = 0; i < 160; ++i) {
        const float a = along(rng), b = across(rng);
        const float edge_x[] = {a, a, b, float(mw - 1) + b}, edge_y[] = {b, float(mh - 1) + b, a * mh / mw, a * mh / mw};
        poses.push_back({edge_x[i % 4], edge_y[i % 4], yaw(rng), scale(rng)});
    }
    ScoreOptions o;
    o.min_valid_fraction = 0.0;
    const auto got = score_and_compare(dut, ref, map.view(), templ.view(), poses, o);
    const auto part = std::count_if(got.begin(), got.end(), [&](const ParticleScore& s) {
        return s.valid_samples > 0 && s.valid_samples < 131 * 97;
    });
    EXPECT_GE(part, 100) << "most poses must straddle an edge";
}

void zero_variance(Backend& dut, Backend& ref) {
    PaddedGray map = textured_image(200, 160, 23);
    cv::rectangle(map.mat(), cv::Rect(20, 20, 80, 70), cv::Scalar(77), cv::FILLED);  // a flat field
    const PaddedGray templ = textured_image(25, 19, 24);
    std::vector<Pose> poses = {{60, 55, 0.3f, 1.0f}, {45, 40, 0, 0.8f}, {150, 100, 1.0f, 1.0f}};
    const auto got = score_and_compare(dut, ref, map.view(), templ.view(), poses, {});
    EXPECT_EQ(got[0].flags, kFlatPatch);
    EXPECT_EQ(got[0].ncc, 0.0f);
    EXPECT_TRUE(got[2].valid());
    // A flat template makes every particle invalid, with scores 0, never NaN.
    std::vector<std::uint8_t> flat(25 * 19, 200);
    const auto flat_scores = score_and_compare(dut, ref, map.view(), GrayView{flat.data(), 25, 19, 25}, poses, {});
    for (const ParticleScore& s : flat_scores) EXPECT_TRUE(s.flags & kFlatTemplate);
}

void yaw_scale_sweep(Backend& dut, Backend& ref) {
    const PaddedGray map = textured_image(400, 400, 29), templ = textured_image(48, 36, 30);
    std::vector<Pose> poses;
    for (int deg = -180; deg < 180; deg += 10)
        for (float s : {0.25f, 0.5f, 1.0f, 1.7f, 3.0f, 4.0f}) poses.push_back({199.5f, 200.25f, float(deg) * std::numbers::pi_v<float> / 180, s});
    score_and_compare(dut, ref, map.view(), templ.view(), poses, {});
}

void large_template(Backend& dut, Backend& ref) {
    std::mt19937 rng(31);
    const PaddedGray map = textured_image(1200, 1000, 31), templ = textured_image(640, 480, 32);
    std::uniform_real_distribution<float> ux(300, 900), uy(250, 750), yaw(-3.1f, 3.1f), sc(0.6f, 1.2f);
    std::vector<Pose> poses(24);
    for (Pose& p : poses) p = {ux(rng), uy(rng), yaw(rng), sc(rng)};
    score_and_compare(dut, ref, map.view(), templ.view(), poses, {});
    ScoreOptions sparse;
    sparse.sampling = Sampling::random(0.1, 7);
    score_and_compare(dut, ref, map.view(), templ.view(), poses, sparse);
}

// The template is cut from the map at a known pose; every backend must rank that pose first.
void best_particle(Backend& dut, Backend& ref) {
    const PaddedGray map = textured_image(500, 400, 37);
    const int tw = 64, th = 48, x0 = 211, y0 = 163;
    cv::Mat templ = map.mat()(cv::Rect(x0, y0, tw, th)).clone();
    std::mt19937 rng(38);
    auto poses = random_poses(rng, 400, 500, 400, 0.0f, 0.9f, 1.1f);
    // Template pixel (u, v) lands on map (x0 + u, y0 + v) when the centre is at x0 + (tw-1)/2.
    poses[123] = {x0 + (tw - 1) / 2.0f, y0 + (th - 1) / 2.0f, 0.0f, 1.0f};
    const auto got = score_and_compare(dut, ref, map.view(), GrayView{templ.data, tw, th, tw}, poses, {});
    const auto best = std::max_element(got.begin(), got.end(), [](auto& a, auto& b) { return a.ncc < b.ncc; });
    EXPECT_EQ(best - got.begin(), 123);
    EXPECT_NEAR(best->ncc, 1.0f, 1e-5f);
}

void repeatable(Backend& dut, Backend&) {
    std::mt19937 rng(41);
    const PaddedGray map = textured_image(320, 240, 41), templ = textured_image(64, 48, 42);
    const auto poses = random_poses(rng, 300, 320, 240, 0.1f, 0.5f, 1.5f);
    const MapHandle h = dut.upload_map(map.view());
    std::vector<ParticleScore> a(poses.size()), b(poses.size());
    const ScoringPlan plan = make_scoring_plan(templ.view(), {});
    dut.score(h, plan, poses, a);
    dut.score(h, plan, poses, b);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(ParticleScore)), 0) << "two identical calls differ";
}

void u8_equals_float_template(Backend& dut, Backend&) {
    std::mt19937 rng(43);
    const PaddedGray map = textured_image(256, 256, 43), templ = textured_image(31, 23, 44);
    std::vector<float> f(31 * 23);
    for (int y = 0; y < 23; ++y)
        for (int x = 0; x < 31; ++x) f[y * 31 + x] = templ.view().at(x, y);
    const auto poses = random_poses(rng, 64, 256, 256, 0.0f, 0.8f, 1.2f);
    const MapHandle h = dut.upload_map(map.view());
    std::vector<ParticleScore> a(64), b(64);
    dut.score(h, templ.view(), poses, {}, a);
    dut.score(h, FloatView{f.data(), 31, 23, 31}, poses, {}, b);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(ParticleScore)), 0);
}

void many_particles(Backend& dut, Backend& ref) {
    std::mt19937 rng(47);
    const PaddedGray map = textured_image(600, 500, 47), templ = textured_image(16, 12, 48);
    score_and_compare(dut, ref, map.view(), templ.view(), random_poses(rng, 20000, 600, 500, 0.05f, 0.5f, 3.0f), {});
}

// 16384 x 16384 (256 MiB): offsets past 2^31 bits of arithmetic must not wrap.
void huge_map(Backend& dut, Backend& ref) {
    const int n = 16384;
    std::vector<std::uint8_t> big(std::size_t(n) * n);
    for (std::size_t y = 0; y < std::size_t(n); ++y)
        for (std::size_t x = 0; x < std::size_t(n); ++x) big[y * n + x] = static_cast<std::uint8_t>((x * 7 + y * 13 + ((x * y) >> 5)) & 0xFF);
    const PaddedGray templ = textured_image(24, 24, 53);
    const std::vector<Pose> poses = {{16370.5f, 16371.25f, 0.2f, 1.0f}, {20.0f, 16360.0f, -0.4f, 1.3f}, {16380.0f, 30.0f, 1.0f, 0.9f},
                                     {8191.5f, 8191.5f, 3.0f, 2.0f},    {16383.0f, 16383.0f, 0.0f, 1.0f}};
    ScoreOptions o;
    o.min_valid_fraction = 0.2;
    score_and_compare(dut, ref, GrayView{big.data(), n, n, n}, templ.view(), poses, o);
}

void real_orthophoto(Backend& dut, Backend& ref) {
    const std::string base = trn::test::shared_data_dir().string();
    const std::string map_path = trn::test::shared_data("orthophoto.png"), frame_path = trn::test::shared_data("realflight/frame_00000.png");
    if (map_path.empty() || frame_path.empty())
        GTEST_SKIP() << "shared data not found (TRN_SHARED_DATA='" << base << "'): real orthophoto case not run";
    // Read as every trnkit command reads images (the device kit's build: libpng, no imgcodecs).
    const GrayImage map = load_gray(map_path), frame = load_gray(frame_path);
    std::mt19937 rng(59);
    const auto poses = random_poses(rng, 200, map.width, map.height, 0.0f, 0.8f, 1.6f);
    score_and_compare(dut, ref, map.view(), frame.view(), poses, {});
}

}  // namespace

std::vector<Case> ncc_cases() {
    return {{"ncc_random_sizes", random_sizes},       {"ncc_sparse_random", sparse_random},
            {"ncc_explicit_points", explicit_points}, {"ncc_strided_rois", strided_rois},
            {"ncc_map_edges", map_edges},             {"ncc_map_edges_long_rows", map_edges_long_rows},
            {"ncc_zero_variance", zero_variance},
            {"ncc_yaw_scale_sweep", yaw_scale_sweep}, {"ncc_large_template", large_template},
            {"ncc_best_particle", best_particle},     {"ncc_repeatable", repeatable},
            {"ncc_u8_equals_float_template", u8_equals_float_template},
            {"ncc_many_particles", many_particles},   {"ncc_huge_map", huge_map},
            {"ncc_real_orthophoto", real_orthophoto}};
}

}  // namespace trn::conformance
