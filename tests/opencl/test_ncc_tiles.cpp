// The NCC kernel's tiling (8 samples per work item, partial tiles at row ends and at the end of a
// sparse list, any number of work items per particle) against cpu-ref, for the shapes the
// conformance suite's default work-group size does not reach.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "opencl_test_support.hpp"
#include "trn/scoring_plan.hpp"

namespace trn::test {
namespace {

constexpr int kMapW = 300, kMapH = 200;

// Poses around the map centre plus some that leave part of a template off the map.
std::vector<Pose> mixed_poses(int count) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> dx(-40.0f, 40.0f), yaw(-3.0f, 3.0f), scale(0.7f, 1.4f);
    std::vector<Pose> poses;
    for (int i = 0; i < count; ++i) poses.push_back({kMapW / 2.0f + dx(rng), kMapH / 2.0f + dx(rng), yaw(rng), scale(rng)});
    poses.push_back({2.0f, 3.0f, 0.3f, 1.0f});                  // mostly outside, top left
    poses.push_back({kMapW - 1.0f, kMapH - 1.0f, -0.2f, 1.1f});  // bottom-right corner
    return poses;
}

struct Shape {
    int templ_w, templ_h;
    double fraction;  // 1: dense
};

std::string shape_text(const Shape& s) {
    return std::to_string(s.templ_w) + "x" + std::to_string(s.templ_h) + (s.fraction < 1 ? " sparse" : " dense");
}

// Scores on `dut` and cpu-ref and compares every particle (same rule as the conformance suite).
void expect_matches_reference(Backend& dut, Backend& ref, const std::vector<std::uint8_t>& map, const Shape& shape) {
    SCOPED_TRACE(shape_text(shape));
    const std::vector<std::uint8_t> templ = textured_pixels(shape.templ_w, shape.templ_h, 5);
    ScoreOptions options;
    if (shape.fraction < 1) options.sampling = Sampling::random(shape.fraction, 11);
    options.min_valid_fraction = 0.0;
    const ScoringPlan plan =
        make_scoring_plan(GrayView{templ.data(), shape.templ_w, shape.templ_h, shape.templ_w}, options);
    const std::vector<Pose> poses = mixed_poses(20);
    const GrayView map_view{map.data(), kMapW, kMapH, kMapW};
    std::vector<ParticleScore> got(poses.size()), want(poses.size()), again(poses.size());
    const MapHandle dut_map = dut.upload_map(map_view);
    dut.score(dut_map, plan, poses, got);
    ref.score(ref.upload_map(map_view), plan, poses, want);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        SCOPED_TRACE("particle " + std::to_string(i));
        EXPECT_EQ(got[i].valid_samples, want[i].valid_samples);
        EXPECT_EQ(got[i].flags, want[i].flags);
        EXPECT_EQ(got[i].ncc, want[i].ncc);
        EXPECT_EQ(got[i].cc, want[i].cc);
        EXPECT_EQ(got[i].ssd, want[i].ssd);
    }
    // Integer sums make a second call bit-identical too.
    dut.score(dut_map, plan, poses, again);
    EXPECT_EQ(std::memcmp(got.data(), again.data(), got.size() * sizeof(ParticleScore)), 0);
}

// Widths below 8 (no whole tile), not a multiple of 8 (partial tiles), exact multiples; sparse sets
// whose size is not a multiple of 8.
const Shape kShapes[] = {{5, 3, 1.0}, {37, 13, 1.0}, {64, 16, 1.0}, {41, 29, 0.37}, {3, 7, 0.5}, {90, 60, 0.1}};

class OpenClNccTiles : public ::testing::TestWithParam<const char*> {};

TEST_P(OpenClNccTiles, MatchesCpuRefForEveryShape) {
    TRN_REQUIRE_OPENCL_DEVICE();
    const std::string group = GetParam();
    ScopedEnv env("TRN_OPENCL_WORK_GROUP", group.empty() ? std::nullopt : std::optional<std::string>(group));
    const auto dut = default_registry().create("opencl", test::backend_options_from_environment());
    const auto ref = default_registry().create("cpu-ref");
    if (!group.empty()) {  // (braces: EXPECT_* is an if/else, GCC 11's -Wdangling-else)
        EXPECT_NE(dut->info().details.find("NCC work-group " + group + ","), std::string::npos) << dut->info().details;
    }
    const std::vector<std::uint8_t> map = textured_pixels(kMapW, kMapH, 3);
    for (const Shape& shape : kShapes) expect_matches_reference(*dut, *ref, map, shape);
}

// "": the device's default; 1 and 2 are smaller than the 7 output words one item per word would need.
INSTANTIATE_TEST_SUITE_P(WorkGroups, OpenClNccTiles, ::testing::Values("", "1", "2", "8", "64", "256"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                             return std::string(info.param).empty() ? std::string("default") : "wg" + std::string(info.param);
                         });

}  // namespace
}  // namespace trn::test
