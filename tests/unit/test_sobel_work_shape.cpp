// Work shapes of the device Sobel kernels come from the device's queries: the work-group follows
// the reported lanes and size limits, rows per item follow the compute units, and the launched
// groups always cover every strip and row.
#include <gtest/gtest.h>

#include "../../backends/common/sobel_work_shape.hpp"

namespace trn {
namespace {

void expect_covers(const SobelWorkShape& s, std::size_t w, std::size_t h) {
    EXPECT_GE(s.group_x, 1u);
    EXPECT_GE(s.group_y, 1u);
    EXPECT_GE(s.rows_per_item, 1u);
    EXPECT_LE(s.rows_per_item, kSobelMaxRowsPerItem);
    EXPECT_GE(s.groups_x * s.group_x * kSobelStripPixels, w);
    EXPECT_GE(s.groups_y * s.group_y * s.rows_per_item, h);
    // No whole group beyond the image.
    EXPECT_LT((s.groups_x - 1) * s.group_x * kSobelStripPixels, std::max<std::size_t>(w, 1));
    EXPECT_LT((s.groups_y - 1) * s.group_y * s.rows_per_item, std::max<std::size_t>(h, 1));
}

TEST(SobelWorkShape, GroupFollowsLanesAndLimits) {
    // A GPU-like report: 32 lanes, 1024 items, 132 compute units.
    const SobelWorkShape gpu = choose_sobel_work_shape({1024, 32, 132}, 1920, 1080);
    EXPECT_EQ(gpu.group_x, 32u);
    EXPECT_EQ(gpu.group_y, 8u);  // 256 items per group
    EXPECT_EQ(gpu.rows_per_item, 1u);  // 132 units want 135k items; 1080p has 130k strip-rows
    expect_covers(gpu, 1920, 1080);

    // PoCL on the 2-core VM: 8 lanes, 4096 items, 2 compute units.
    const SobelWorkShape pocl = choose_sobel_work_shape({4096, 8, 2}, 1920, 1080);
    EXPECT_EQ(pocl.group_x, 8u);
    EXPECT_EQ(pocl.group_y, 32u);
    EXPECT_EQ(pocl.rows_per_item, kSobelMaxRowsPerItem);
    expect_covers(pocl, 1920, 1080);

    // A kernel that allows only 64 items, a 64-wide subgroup, and a small y extent.
    WorkGroupLimits small{64, 64, 4};
    small.max_group_y = 1;
    const SobelWorkShape s = choose_sobel_work_shape(small, 100, 3);
    EXPECT_EQ(s.group_x, 64u);
    EXPECT_EQ(s.group_y, 1u);
    expect_covers(s, 100, 3);
}

TEST(SobelWorkShape, OddReportsStillGiveAValidShape) {
    for (const WorkGroupLimits& l : {WorkGroupLimits{0, 0, 0}, WorkGroupLimits{1, 1, 1}, WorkGroupLimits{3, 48, 0},
                                     WorkGroupLimits{100000, 7, 1000}}) {
        for (const auto& [w, h] : {std::pair<std::size_t, std::size_t>{1, 1}, {1, 300}, {300, 1}, {17, 5}, {1920, 1080}}) {
            SCOPED_TRACE(std::to_string(l.max_group_size) + "/" + std::to_string(l.lanes) + " " + std::to_string(w) + "x" +
                         std::to_string(h));
            const SobelWorkShape s = choose_sobel_work_shape(l, w, h);
            EXPECT_LE(s.group_x * s.group_y, std::max<std::size_t>(l.max_group_size, 1));
            expect_covers(s, w, h);
        }
    }
}

TEST(SobelWorkShape, UnknownComputeUnitsAimAtSixtyFourGroups) {
    // Vulkan reports no compute units: lavapipe-like 8 lanes, 1024 items.
    const SobelWorkShape s = choose_sobel_work_shape({1024, 8, 0}, 1920, 1080);
    EXPECT_EQ(s.rows_per_item, 1920u / 16 * 1080 / (64 * 256));
    expect_covers(s, 1920, 1080);
}

}  // namespace
}  // namespace trn
