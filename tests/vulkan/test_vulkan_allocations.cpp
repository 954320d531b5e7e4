// Steady-state Vulkan calls allocate nothing on the host (issue 6): after a warm-up call, repeated
// score and sobel calls with inputs of the same or smaller size make no operator new call. The
// validation layer is switched off here because it is C++ and allocates for its own bookkeeping,
// which would be counted too.
#include <span>
#include <vector>

#include "counting_new.hpp"
#include "vulkan_test_support.hpp"

namespace trn::test {
namespace {

constexpr int kRepeats = 5;

std::unique_ptr<Backend> unvalidated_vulkan(bool force_staging = false) {
    return vulkan_with([&](auto& v) {
        v.validation = false;
        v.force_staging = force_staging;
    });
}

TEST(VulkanAllocations, CounterSeesOperatorNew) {
    // Without this the tests below could pass with a counter that never counts.
    const std::uint64_t before = operator_new_calls();
    auto p = std::make_unique<std::vector<int>>(100);
    EXPECT_GE(operator_new_calls() - before, 2u);
}

// Scores `poses` kRepeats times after one warm-up call; returns the operator new calls of the repeats.
std::uint64_t allocations_of_repeated_scores(Backend& backend, const ScoreOptions& options, int pose_count) {
    const PaddedGray map = textured_image(400, 300, 21);
    const PaddedGray templ = textured_image(64, 48, 22);
    const MapHandle handle = backend.upload_map(map.view());
    const ScoringPlan plan = make_scoring_plan(templ.view(), options);
    const std::vector<Pose> poses = random_poses(pose_count, map.width, map.height, 23);
    std::vector<ParticleScore> out(poses.size());
    PhaseTimes times;
    backend.score(handle, plan, poses, out, &times);  // warm-up: pipeline and buffers created here
    const std::uint64_t before = operator_new_calls();
    for (int r = 0; r < kRepeats; ++r) {
        backend.score(handle, plan, poses, out, &times);
        backend.score(handle, plan, std::span(poses).first(pose_count / 2), out, nullptr);  // fewer poses
    }
    const std::uint64_t calls = operator_new_calls() - before;
    int valid = 0;
    for (const ParticleScore& s : out) valid += s.valid();
    EXPECT_GT(valid, 0) << "the scores should be real";
    return calls;
}

TEST(VulkanAllocations, RepeatedDenseScoresAllocateNothing) {
    TRN_REQUIRE_VULKAN();
    auto backend = unvalidated_vulkan();
    EXPECT_EQ(allocations_of_repeated_scores(*backend, ScoreOptions{}, 64), 0u) << "operator new calls in steady state";
}

TEST(VulkanAllocations, RepeatedSparseScoresAllocateNothing) {
    TRN_REQUIRE_VULKAN();
    auto backend = unvalidated_vulkan();
    ScoreOptions options;
    options.sampling = Sampling::random(0.1, 7);
    options.min_valid_fraction = 0.5;
    EXPECT_EQ(allocations_of_repeated_scores(*backend, options, 64), 0u) << "operator new calls in steady state";
}

TEST(VulkanAllocations, RepeatedScoresOnTheStagingPathAllocateNothing) {
    TRN_REQUIRE_VULKAN();
    std::unique_ptr<Backend> backend = unvalidated_vulkan(true);
    EXPECT_EQ(allocations_of_repeated_scores(*backend, ScoreOptions{}, 64), 0u) << "operator new calls in steady state";
}

TEST(VulkanAllocations, RepeatedSobelsAllocateNothing) {
    TRN_REQUIRE_VULKAN();
    auto backend = unvalidated_vulkan();
    const PaddedGray src = noise_image(320, 240, 31);
    std::vector<std::int16_t> gx(std::size_t(src.width) * src.height), gy(gx.size());
    const Int16View gx_view{gx.data(), src.width, src.height, src.width}, gy_view{gy.data(), src.width, src.height, src.width};
    PhaseTimes times;
    backend->sobel(src.view(), gx_view, gy_view, &times);  // warm-up
    const std::vector<std::int16_t> first_gx = gx;
    const std::uint64_t before = operator_new_calls();
    for (int r = 0; r < kRepeats; ++r) {
        backend->sobel(src.view(), gx_view, gy_view, &times);
        backend->sobel(src.view().roi(0, 0, 100, 80), gx_view.roi(0, 0, 100, 80), gy_view.roi(0, 0, 100, 80), nullptr);
    }
    EXPECT_EQ(operator_new_calls() - before, 0u) << "operator new calls in steady state";
    EXPECT_NE(gx, first_gx) << "the smaller calls should have written the top-left corner";
}

}  // namespace
}  // namespace trn::test
