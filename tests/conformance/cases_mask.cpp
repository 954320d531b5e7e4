// No-data cases: maps uploaded with a validity mask (holes, strips, single pixels, the real
// orthomosaic's transparency), every backend against cpu-ref bit for bit, plus a check of the rule
// itself that does not trust cpu-ref: the valid-sample counts computed here from the positions, and
// the NCC over exactly those samples in double precision.
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
#include "trn/fixed_point.hpp"
#include "trn/io/image_io.hpp"
#include "../common/shared_data.hpp"

namespace trn::conformance {
namespace {

using test::PaddedGray;
using test::textured_image;

// Validity with round holes, a no-data band along one edge and single invalid pixels, as an
// orthomosaic's transparency looks (255 valid, 0 no-data), in a padded buffer (stride > width).
PaddedGray holes_mask(int w, int h, std::uint32_t seed) {
    PaddedGray m{w, h, 3, std::vector<std::uint8_t>(std::size_t(w + 6) * (h + 6), 0x5A)};
    cv::Mat v = m.mat();
    v.setTo(255);
    std::mt19937 rng(seed);
    for (int k = 0; k < 6; ++k)
        cv::circle(v, {int(rng() % w), int(rng() % h)}, 3 + int(rng() % (std::min(w, h) / 6)), cv::Scalar(0), cv::FILLED);
    cv::rectangle(v, cv::Rect(0, 0, std::max(1, w / 12), h), cv::Scalar(0), cv::FILLED);
    for (int k = 0; k < 40; ++k) v.at<std::uint8_t>(int(rng() % h), int(rng() % w)) = 0;
    v.at<std::uint8_t>(h - 1, w - 1) = 0;  // the last cell
    return m;
}

void masked_random(Backend& dut, Backend& ref) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        std::mt19937 rng(seed);
        const int mw = 60 + int(rng() % 300), mh = 60 + int(rng() % 300);
        const PaddedGray map = textured_image(mw, mh, seed), valid = holes_mask(mw, mh, seed);
        const PaddedGray templ = textured_image(9 + int(rng() % 40), 7 + int(rng() % 30), seed + 50);
        const auto poses = random_poses(rng, 151, mw, mh, 0.05f, 0.5f, 1.8f);
        SCOPED_TRACE("seed " + std::to_string(seed));
        for (double min_valid : {0.9, 0.3, 0.0}) {
            ScoreOptions o;
            o.min_valid_fraction = min_valid;
            score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
            o.sampling = Sampling::random(0.3, seed);
            score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
        }
    }
}

// Large templates mostly over valid cells: the fast paths (cpu: AVX2 when the patch's tiles are all
// valid) beside the checked ones in one batch.
void masked_large_template(Backend& dut, Backend& ref) {
    std::mt19937 rng(7);
    const PaddedGray map = textured_image(900, 700, 7), templ = textured_image(200, 150, 8);
    PaddedGray valid{900, 700, 0, std::vector<std::uint8_t>(900 * 700, 255)};
    cv::circle(valid.mat(), {600, 350}, 60, cv::Scalar(0), cv::FILLED);
    valid.mat().at<std::uint8_t>(100, 800) = 0;
    std::vector<Pose> poses;
    std::uniform_real_distribution<float> ux(150, 750), uy(120, 580), yaw(-3.1f, 3.1f), sc(0.8f, 1.2f);
    for (int i = 0; i < 40; ++i) poses.push_back({ux(rng), uy(rng), yaw(rng), sc(rng)});
    poses.push_back({250, 350, 0.3f, 1.0f});  // far from every hole
    for (double min_valid : {0.9, 0.0}) {
        ScoreOptions o;
        o.min_valid_fraction = min_valid;
        score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
    }
}

// One invalid pixel takes out exactly the (up to) four cells that hold it: poses on integer
// positions at scale 1, yaw 0, so samples land on pixel centres (weights 0 included).
void masked_single_pixels(Backend& dut, Backend& ref) {
    const int mw = 64, mh = 48;
    const PaddedGray map = textured_image(mw, mh, 11), templ = textured_image(8, 6, 12);
    for (const cv::Point bad : {cv::Point(0, 0), cv::Point(mw - 1, mh - 1), cv::Point(mw - 2, 10), cv::Point(31, 23), cv::Point(32, 0)}) {
        PaddedGray valid{mw, mh, 0, std::vector<std::uint8_t>(mw * mh, 1)};  // any non-zero value is valid
        valid.mat().at<std::uint8_t>(bad) = 0;
        std::vector<Pose> poses;
        for (float y = 2.5f; y < mh; y += 3.0f)
            for (float x = 3.5f; x < mw; x += 3.0f) poses.push_back({x, y, 0.0f, 1.0f});
        ScoreOptions o;
        o.min_valid_fraction = 0.0;
        SCOPED_TRACE("invalid pixel (" + std::to_string(bad.x) + ", " + std::to_string(bad.y) + ")");
        const auto got = score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
        EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.valid_samples == 48; }));
        EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.valid_samples > 0 && s.valid_samples < 48; }));
    }
}

// A mask with nothing invalid, or whose no-data no particle reaches, gives the unmasked bits.
void masked_same_as_unmasked(Backend& dut, Backend&) {
    std::mt19937 rng(13);
    const PaddedGray map = textured_image(400, 300, 13), templ = textured_image(64, 48, 14);
    PaddedGray all{400, 300, 0, std::vector<std::uint8_t>(400 * 300, 255)}, corner = all;
    cv::rectangle(corner.mat(), cv::Rect(380, 280, 20, 20), cv::Scalar(0), cv::FILLED);
    std::vector<Pose> poses;
    std::uniform_real_distribution<float> ux(60, 300), uy(60, 220), yaw(-3.1f, 3.1f), sc(0.7f, 1.2f);
    for (int i = 0; i < 64; ++i) poses.push_back({ux(rng), uy(rng), yaw(rng), sc(rng)});
    const ScoringPlan plan = make_scoring_plan(templ.view(), {});
    std::vector<ParticleScore> plain(poses.size()), with_all(poses.size()), with_corner(poses.size());
    dut.score(dut.upload_map(map.view()), plan, poses, plain);
    const MapHandle h_all = dut.upload_map(map.view(), all.view()), h_corner = dut.upload_map(map.view(), corner.view());
    EXPECT_FALSE(h_all->masked());
    EXPECT_TRUE(h_corner->masked());
    dut.score(h_all, plan, poses, with_all);
    dut.score(h_corner, plan, poses, with_corner);
    EXPECT_EQ(std::memcmp(plain.data(), with_all.data(), plain.size() * sizeof(ParticleScore)), 0);
    EXPECT_EQ(std::memcmp(plain.data(), with_corner.data(), plain.size() * sizeof(ParticleScore)), 0);
}

// The rule, computed here: a sample counts when its position is inside the map and the four
// pixels of its cell are valid; NCC over those samples in double precision.
void masked_rule(Backend& dut, Backend&) {
    std::mt19937 rng(17);
    const int mw = 160, mh = 120;
    const PaddedGray map = textured_image(mw, mh, 17), valid = holes_mask(mw, mh, 17), templ = textured_image(21, 15, 18);
    const auto poses = random_poses(rng, 120, mw, mh, 0.05f, 0.7f, 1.5f);
    ScoreOptions o;
    o.min_valid_fraction = 0.0;
    const ScoringPlan plan = make_scoring_plan(templ.view(), o);
    std::vector<ParticleScore> got(poses.size());
    dut.score(dut.upload_map(map.view(), valid.view()), plan, poses, got);
    const GrayView m = map.view(), v = valid.view(), t = templ.view();
    int partly = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const Affine A = pose_to_affine(poses[i]);
        double n = 0, si = 0, sii = 0, st = 0, stt = 0, sit = 0;
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x) {
                volatile float du = float(x) - plan.cx, dv = float(y) - plan.cy;
                volatile float ax = A.a * du, bx = A.b * dv, cy = A.c * du, dy = A.d * dv;
                volatile float sx = A.tx + ax, sy = A.ty + cy;
                const float px = sx + bx, py = sy + dy;
                if (!(px >= 0 && py >= 0 && px <= float(mw - 1) && py <= float(mh - 1))) continue;
                const int x0 = std::min(int(px), mw - 2), y0 = std::min(int(py), mh - 2);
                if (!v.at(x0, y0) || !v.at(x0 + 1, y0) || !v.at(x0, y0 + 1) || !v.at(x0 + 1, y0 + 1)) continue;
                const double fx = px - x0, fy = py - y0;
                const double top = m.at(x0, y0) * (1 - fx) + m.at(x0 + 1, y0) * fx;
                const double bot = m.at(x0, y0 + 1) * (1 - fx) + m.at(x0 + 1, y0 + 1) * fx;
                const double value = top * (1 - fy) + bot * fy, tv = t.at(x, y);
                n += 1, si += value, sii += value * value, st += tv, stt += tv * tv, sit += value * tv;
            }
        SCOPED_TRACE("pose " + std::to_string(i));
        EXPECT_EQ(got[i].valid_samples, std::uint32_t(n));
        if (n > 0 && n < t.width * t.height) ++partly;
        const double vi = n * sii - si * si, vt = n * stt - st * st;
        if (got[i].valid() && vi > n * n * 1.0 && vt > 0) {
            EXPECT_NEAR(got[i].ncc, (n * sit - si * st) / std::sqrt(vi * vt), 2e-3);  // 7-bit weights vs exact
        }
    }
    EXPECT_GT(partly, 10) << "too few poses partly over no-data to test the rule";
}

// The cpu backend cuts a patch near no-data into tiles of 8 rows x 32 samples judged from their
// corners, and samples rows in 16-sample steps with a masked last step: templates of widths and
// heights around those sizes, on no-data that is fine-grained (stripes, a checkerboard of 8x8 and
// 5x5 squares, single pixels, a hole) and coarse, poses of any yaw and scale over the map's edges,
// plus axis-aligned poses on whole pixels up to the last column and row (weights 0, px = W-1).
void masked_tiles(Backend& dut, Backend& ref) {
    const int mw = 181, mh = 143;
    const PaddedGray map = textured_image(mw, mh, 23);
    PaddedGray valid{mw, mh, 0, std::vector<std::uint8_t>(std::size_t(mw) * mh, 255)};
    cv::Mat v = valid.mat();
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 90; ++x)
            if (((x / 8) + (y / 8)) % 2 == 0 && x < 48) v.at<std::uint8_t>(y, x) = 0;  // 8x8 checkerboard
            else if (x >= 48 && ((x / 5) + (y / 5)) % 2 == 0) v.at<std::uint8_t>(y, x) = 0;  // 5x5 checkerboard
    cv::rectangle(v, cv::Rect(100, 0, 3, mh), cv::Scalar(0), cv::FILLED);  // a stripe
    cv::circle(v, {140, 100}, 25, cv::Scalar(0), cv::FILLED);
    for (int k = 0; k < 30; ++k) v.at<std::uint8_t>(70 + (k * 7) % 70, 5 + (k * 13) % 90) = 0;
    std::mt19937 rng(23);
    auto poses = random_poses(rng, 60, mw, mh, 0.1f, 0.4f, 2.5f);
    for (float yaw : {0.0f, std::numbers::pi_v<float> / 2})
        for (float y : {20.0f, 71.0f, float(mh - 5)})
            for (float x : {10.0f, 95.0f, float(mw - 5)}) poses.push_back({x, y, yaw, 1.0f});
    for (const cv::Size ts : {cv::Size(2, 2), cv::Size(7, 9), cv::Size(15, 8), cv::Size(16, 17), cv::Size(17, 7), cv::Size(31, 16),
                              cv::Size(32, 8), cv::Size(33, 15), cv::Size(48, 3), cv::Size(64, 24), cv::Size(65, 9)}) {
        const PaddedGray templ = textured_image(ts.width, ts.height, 24 + ts.width);
        SCOPED_TRACE("template " + std::to_string(ts.width) + "x" + std::to_string(ts.height));
        ScoreOptions o;
        o.min_valid_fraction = 0.0;
        score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
        o.sampling = Sampling::random(0.5, 3);
        score_and_compare(dut, ref, map.view(), valid.view(), templ.view(), poses, o);
    }
}

// The real orthomosaic of ../shared/data/realflight2 (transparent no-data) with a real frame.
void masked_real_orthomosaic(Backend& dut, Backend& ref) {
    const std::string base = trn::test::shared_data_dir().string();
    const std::string map_path = trn::test::shared_data("realflight2/orthomosaic.png"),
                      frame_path = trn::test::shared_data("realflight2/frames/frame_00000.png");
    if (map_path.empty() || frame_path.empty())
        GTEST_SKIP() << "shared data not found (TRN_SHARED_DATA='" << base << "'): real orthomosaic case not run";
    // Read as every trnkit command reads maps (the device kit's build: libpng, no imgcodecs).
    const GrayImage grey = load_gray(map_path), alpha = load_validity(map_path), frame = load_gray(frame_path);
    ASSERT_EQ(alpha.width, grey.width) << "the orthomosaic has no alpha";
    std::mt19937 rng(19);
    const auto poses = random_poses(rng, 150, grey.width, grey.height, 0.05f, 0.6f, 0.75f);
    ScoreOptions o;
    o.sampling = Sampling::random(0.2, 5);
    const auto got = score_and_compare(dut, ref, grey.view(), alpha.view(), frame.view(), poses, o);
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.valid(); }));
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [](const ParticleScore& s) { return s.flags & kTooFewSamples; }));
}

void mask_errors(Backend& dut, Backend&) {
    const PaddedGray map = textured_image(50, 40, 1);
    std::vector<std::uint8_t> small(49 * 40, 255), none(50 * 40, 0), one_cell(50 * 40, 0);
    expect_error([&] { dut.upload_map(map.view(), GrayView{small.data(), 49, 40, 49}); }, "validity mask 49x40 differs from the map 50x40");
    expect_error([&] { dut.upload_map(map.view(), GrayView{none.data(), 50, 40, 50}); }, "leaves no 2x2 cell");
    expect_error([&] { dut.upload_map(map.view(), GrayView{small.data(), 50, 40, 10}); }, "stride 10 is smaller");
    one_cell[0] = one_cell[1] = one_cell[50] = one_cell[51] = 7;  // one valid cell is enough
    EXPECT_TRUE(dut.upload_map(map.view(), GrayView{one_cell.data(), 50, 40, 50})->masked());
}

}  // namespace

std::vector<Case> mask_cases() {
    return {{"mask_random", masked_random},
            {"mask_large_template", masked_large_template},
            {"mask_single_pixels", masked_single_pixels},
            {"mask_same_as_unmasked", masked_same_as_unmasked},
            {"mask_rule", masked_rule},
            {"mask_tiles", masked_tiles},
            {"mask_real_orthomosaic", masked_real_orthomosaic},
            {"mask_errors", mask_errors}};
}

}  // namespace trn::conformance
