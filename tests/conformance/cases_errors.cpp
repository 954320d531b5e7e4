// Bad input is refused identically on every backend, with a message naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../common/test_images.hpp"
#include "cases.hpp"
#include "checks.hpp"

namespace trn::conformance {
namespace {

void bad_input(Backend& dut, Backend& ref) {
    const auto map = test::textured_image(50, 40, 1), templ = test::textured_image(20, 10, 2), big = test::textured_image(60, 10, 3);
    const MapHandle h = dut.upload_map(map.view());
    std::vector<ParticleScore> out(4);
    std::vector<Pose> poses = {{25, 20, 0, 1}, {25, 20, 0, 1}};
    poses[1].x = std::numeric_limits<float>::quiet_NaN();
    expect_error([&] { dut.score(h, templ.view(), poses, {}, out); }, "pose 1 has a non-finite x");
    poses[1] = {25, 20, 0, -1};
    expect_error([&] { dut.score(h, templ.view(), poses, {}, out); }, "pose 1 has scale");
    poses[1] = {25, 20, 0, 1};
    expect_error([&] { dut.score(h, big.view(), poses, {}, out); }, "smaller than the template");
    expect_error([&] { dut.score(ref.upload_map(map.view()), templ.view(), poses, {}, out); }, "another backend");
    expect_error([&] { dut.score(h, templ.view(), poses, {}, std::span(out).first(1)); }, "output holds 1 scores for 2 poses");
    expect_error([&] { dut.upload_map(GrayView{map.view().data, 1, 5, 1}); }, "smaller than 2x2");
    ScoreOptions o;
    o.sampling = Sampling::random(1.5, 1);
    expect_error([&] { dut.score(h, templ.view(), poses, o, out); }, "sampling fraction");
    std::vector<std::int16_t> g(50 * 40);
    expect_error([&] { dut.sobel(map.view(), {g.data(), 49, 40, 50}, {g.data(), 50, 40, 50}); }, "differs from the source");
    // Nothing was written by the refused calls.
    for (const ParticleScore& s : out) EXPECT_EQ(s.flags, 0u);
}

void phase_times(Backend& dut, Backend&) {
    const auto map = test::textured_image(300, 200, 4), templ = test::textured_image(30, 20, 5);
    PhaseTimes t{-1, -1, -1};
    const MapHandle h = dut.upload_map(map.view(), &t);
    EXPECT_GE(t.upload_ms, 0.0);
    std::vector<Pose> poses(100, Pose{150, 100, 0.1f, 1.0f});
    std::vector<ParticleScore> out(100);
    t = {-1, -1, -1};
    dut.score(h, templ.view(), poses, {}, out, &t);
    for (double v : {t.upload_ms, t.execute_ms, t.download_ms}) EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << v;
    EXPECT_GT(t.total_ms(), 0.0);
}

}  // namespace

std::vector<Case> error_cases() { return {{"errors_bad_input", bad_input}, {"phase_times", phase_times}}; }

}  // namespace trn::conformance
