// The CUDA backend's host-side planning (cuda_plan.hpp): what it passes to the kernels and what it
// refuses, checked without a GPU.
#include <gtest/gtest.h>

#include <string>

#include "cuda_plan.hpp"
#include "trn/error.hpp"

namespace trn::cuda {
namespace {

std::string error_of(const auto& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

ScoringPlan dense_plan(int w, int h) {
    std::vector<std::uint8_t> pixels(std::size_t(w) * h);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::uint8_t(i * 37 % 251);
    return make_scoring_plan(GrayView{pixels.data(), w, h, w}, {});
}

TEST(CudaPlan, BlockSizeFromTheRuleOrTheOption) {
    EXPECT_EQ(ncc_block_size(0, 256, 1024), 256u);
    EXPECT_EQ(ncc_block_size(0, 256, 128), 128u);  // the kernel's register limit wins
    EXPECT_EQ(ncc_block_size(64, 256, 1024), 64u);
    EXPECT_NE(error_of([] { ncc_block_size(48, 256, 1024); }).find("BackendOptions.cuda.work_group = 48: expected a power of two from 32 to 1024"),
              std::string::npos);
    EXPECT_NE(error_of([] { ncc_block_size(16, 256, 1024); }).find("work_group = 16"), std::string::npos);
    EXPECT_NE(error_of([] { ncc_block_size(2048, 256, 1024); }).find("work_group = 2048"), std::string::npos);
    EXPECT_NE(error_of([] { ncc_block_size(512, 256, 256); }).find("at most 256 threads per block"), std::string::npos);
    EXPECT_NE(error_of([] { ncc_block_size(0, 32, 16); }).find("less than one warp"), std::string::npos);
}

TEST(CudaPlan, DenseArgumentsAndSizes) {
    const ScoringPlan plan = dense_plan(33, 17);
    const NccLaunch l = plan_ncc(plan, 1000, 640, 480, 0, 256, {});
    EXPECT_EQ(l.grid, 1000u);
    EXPECT_EQ(l.block, 256u);
    EXPECT_EQ(l.args.map_w, 640);
    EXPECT_EQ(l.args.map_h, 480);
    EXPECT_EQ(l.args.mask_words, 0);
    EXPECT_EQ(l.args.templ_w, 33);
    EXPECT_EQ(l.args.templ_h, 17);
    EXPECT_EQ(l.args.cx, 16.0f);
    EXPECT_EQ(l.args.cy, 8.0f);
    EXPECT_EQ(l.args.count, 0);
    EXPECT_EQ(l.args.map, 0u);  // pointers are the backend's to fill
    EXPECT_EQ(l.affine_bytes, 1000u * 8 * 4);
    EXPECT_EQ(l.sums_bytes, 1000u * 6 * 8);
    EXPECT_EQ(l.quantized_bytes, 33u * 17 * 4);
    EXPECT_EQ(l.offsets_bytes, 0u);
}

TEST(CudaPlan, SparseArgumentsAndOffsets) {
    std::vector<std::uint8_t> pixels(64 * 48, 0);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::uint8_t(i % 200);
    ScoreOptions o;
    o.sampling = Sampling::random(0.1, 7);
    const ScoringPlan plan = make_scoring_plan(GrayView{pixels.data(), 64, 48, 64}, o);
    const NccLaunch l = plan_ncc(plan, 5, 100, 100, 4, 128, {});
    EXPECT_EQ(l.args.count, static_cast<std::int32_t>(plan.sample_count()));
    EXPECT_EQ(l.args.mask_words, 4);
    EXPECT_EQ(l.offsets_bytes, plan.sample_count() * 8);
    std::vector<float> offsets;
    sample_offsets(plan, offsets);
    ASSERT_EQ(offsets.size(), 2 * plan.sample_count());
    for (std::size_t k = 0; k < plan.points.size(); ++k) {
        EXPECT_EQ(offsets[2 * k], float(plan.points[k].u) - plan.cx);
        EXPECT_EQ(offsets[2 * k + 1], float(plan.points[k].v) - plan.cy);
    }
}

TEST(CudaPlan, RefusesWhatTheKernelsCannotIndex) {
    const ScoringPlan plan = dense_plan(8, 8);
    GridLimits small;
    small.max_grid_x = 100;
    EXPECT_NE(error_of([&] { plan_ncc(plan, 101, 64, 64, 0, 32, small); }).find("1 to 100 particles per call"), std::string::npos);
    EXPECT_NO_THROW(plan_ncc(plan, 100, 64, 64, 0, 32, small));
}

TEST(CudaPlan, AffinesAreThePlansOwn) {
    const Pose poses[2] = {{10.5f, 20.25f, 0.3f, 1.5f}, {1, 2, -2.0f, 0.5f}};
    std::vector<float> out;
    affines_of(poses, 2, out);
    ASSERT_EQ(out.size(), 16u);
    for (int i = 0; i < 2; ++i) {
        const Affine A = pose_to_affine(poses[i]);
        const float want[8] = {A.a, A.b, A.c, A.d, A.tx, A.ty, 0, 0};
        for (int k = 0; k < 8; ++k) EXPECT_EQ(out[std::size_t(8 * i + k)], want[k]);
    }
}

TEST(CudaPlan, SobelLayoutIsAlignedAndCoversTheImage) {
    WorkGroupLimits lim;
    lim.max_group_size = 1024;
    lim.lanes = 32;
    lim.compute_units = 132;
    lim.max_group_y = 1024;
    for (const auto& [w, h] : {std::pair<std::size_t, std::size_t>{1920, 1080}, {1, 1}, {17, 3}, {65536, 2}, {640, 480}}) {
        const SobelLaunch l = plan_sobel(w, h, lim, {});
        EXPECT_EQ(l.args.pitch % 64, 0) << w;
        // The right neighbour and the last strip's read past it stay inside the row.
        EXPECT_GE(std::size_t(l.args.pitch), TRN_SOBEL_PAD + (w + 15) / 16 * 16 + 1) << w;
        EXPECT_EQ(l.args.out_pitch % 16, 0);
        EXPECT_GE(std::size_t(l.args.out_pitch), w);
        EXPECT_EQ(l.src_bytes, std::size_t(l.args.pitch) * h);
        EXPECT_EQ(l.out_bytes, std::size_t(l.args.out_pitch) * h * 2);
        EXPECT_GE(l.columns_grid * l.columns_block, 2 * h);
        EXPECT_GE(l.shape.groups_x * l.shape.group_x * 16, w);
        EXPECT_GE(l.shape.groups_y * l.shape.group_y * l.shape.rows_per_item, h);
        EXPECT_EQ(std::size_t(l.args.rows_per_item), l.shape.rows_per_item);
        EXPECT_LE(l.shape.group_x * l.shape.group_y, 1024u);
    }
}

TEST(CudaPlan, TallImagesTakeMoreRowsWhereTheGridIsSmall) {
    WorkGroupLimits one_warp;
    one_warp.max_group_size = 32;
    one_warp.lanes = 32;
    one_warp.compute_units = 100000;  // many units: one row per thread, were the grid large enough
    one_warp.max_group_y = 1;
    GridLimits grid;
    grid.max_grid_y = 1000;
    const SobelLaunch l = plan_sobel(64, 65536, one_warp, grid);
    EXPECT_LE(l.shape.groups_y, 1000u);
    EXPECT_GE(l.shape.groups_y * l.shape.group_y * l.shape.rows_per_item, 65536u);
}

TEST(CudaPlan, MapsBeyondFreeMemoryAreRefusedByName) {
    EXPECT_NO_THROW(check_fits("upload_map: map 100x100", 10000, 10000, 20000, "cuda:0 (X)"));
    const std::string e = error_of([] { check_fits("upload_map: map 40000x40000 (1525 MiB)", 1600000000, 1 << 30, 2u << 30, "cuda:0 (Orin)"); });
    EXPECT_NE(e.find("upload_map: map 40000x40000 (1525 MiB) needs 1525 MiB, more than the free memory of cuda:0 (Orin): 1024 MiB free of 2048 MiB (cuMemGetInfo)"),
              std::string::npos) << e;
}

}  // namespace
}  // namespace trn::cuda
