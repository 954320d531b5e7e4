// The device NCC kernels' work-group shapes come from the device's queries (lanes, size limit,
// local memory and whether it is host memory), never from the device type.
#include <gtest/gtest.h>

#include "../../backends/common/ncc_work_shape.hpp"

namespace trn {
namespace {

bool is_pow2(std::size_t v) { return v != 0 && (v & (v - 1)) == 0; }

NccDeviceLimits limits(std::size_t max_group, std::size_t lanes, std::size_t local_bytes, bool host_memory) {
    NccDeviceLimits l;
    l.max_group_size = max_group;
    l.lanes = lanes;
    l.local_memory_bytes = local_bytes;
    l.local_memory_is_host_memory = host_memory;
    return l;
}

TEST(NccWorkShape, OpenClFollowsLanesLimitsAndLocalMemory) {
    // PoCL on this VM: 4096 items, 8 lanes, 512 KiB of "local" memory that is global memory.
    const NccWorkShape pocl = choose_opencl_ncc_shape(limits(4096, 8, 512 << 10, true));
    EXPECT_EQ(pocl.group_size, 1u);
    EXPECT_EQ(pocl.particles_per_group, 1u);
    // NVIDIA-like: 1024 items, 32-wide warps, 48 KiB local memory: 8 warps.
    EXPECT_EQ(choose_opencl_ncc_shape(limits(1024, 32, 48 << 10, false)).group_size, 256u);
    // AMD-like 64-wide wavefronts: 8 of them would be 512, capped at 256.
    EXPECT_EQ(choose_opencl_ncc_shape(limits(1024, 64, 64 << 10, false)).group_size, 256u);
    // Intel-like 16 lanes: 128.
    EXPECT_EQ(choose_opencl_ncc_shape(limits(512, 16, 64 << 10, false)).group_size, 128u);
    // The device's maximum limits it.
    EXPECT_EQ(choose_opencl_ncc_shape(limits(64, 32, 48 << 10, false)).group_size, 64u);
    // The reduction's 48 bytes per item must fit in local memory: 4 KiB holds 85 -> 64.
    EXPECT_EQ(choose_opencl_ncc_shape(limits(1024, 32, 4096, false)).group_size, 64u);
    // Lanes that are not a power of two round down (48 -> 32 -> 256 items).
    EXPECT_EQ(choose_opencl_ncc_shape(limits(1024, 48, 48 << 10, false)).group_size, 256u);
}

TEST(NccWorkShape, VulkanFollowsSubgroupAndHostMemory) {
    // lavapipe (256-bit): subgroups of 8, every memory type host memory: one subgroup, 8 particles.
    const NccWorkShape lvp = choose_vulkan_ncc_shape(limits(1024, 8, 32 << 10, true));
    EXPECT_EQ(lvp.group_size, 8u);
    EXPECT_EQ(lvp.particles_per_group, kVulkanHostParticles);
    // lavapipe built for 128-bit SIMD: subgroups of 4.
    EXPECT_EQ(choose_vulkan_ncc_shape(limits(1024, 4, 32 << 10, true)).group_size, 4u);
    // A GPU with 32-wide subgroups: 8 subgroups, one particle per group.
    const NccWorkShape gpu = choose_vulkan_ncc_shape(limits(1024, 32, 48 << 10, false));
    EXPECT_EQ(gpu.group_size, 256u);
    EXPECT_EQ(gpu.particles_per_group, 1u);
    // Mali-like 16-wide subgroups and at most 128 invocations.
    EXPECT_EQ(choose_vulkan_ncc_shape(limits(128, 16, 32 << 10, false)).group_size, 128u);
    // Integrated GPU with 8-wide subgroups and its own (non-host) memory types: 64, one particle.
    const NccWorkShape igpu = choose_vulkan_ncc_shape(limits(1024, 8, 64 << 10, false));
    EXPECT_EQ(igpu.group_size, 64u);
    EXPECT_EQ(igpu.particles_per_group, 1u);
}

TEST(NccWorkShape, CudaTakesWholeWarps) {
    // H200-like: 1024 threads, warps of 32: 8 warps.
    EXPECT_EQ(choose_cuda_ncc_shape(limits(1024, 32, 48 << 10, false)).group_size, 256u);
    // A kernel whose registers allow only 128 threads per block.
    EXPECT_EQ(choose_cuda_ncc_shape(limits(128, 32, 48 << 10, false)).group_size, 128u);
    // Never below one warp: the backend refuses a kernel that allows less (cuda_plan.cpp).
    EXPECT_EQ(choose_cuda_ncc_shape(limits(16, 32, 48 << 10, false)).group_size, 32u);
    EXPECT_EQ(choose_cuda_ncc_shape(limits(1024, 32, 48 << 10, false)).particles_per_group, 1u);
}

TEST(NccWorkShape, VulkanGroupsWidenSoNoItemOutrunsLavapipesLoopBudget) {
    // lavapipe on aarch64: 4-wide subgroups, a 640x480 template (307200 samples): 4 items would walk
    // 76800 each; 16 walk 19200.
    EXPECT_EQ(vulkan_group_for_samples(4, 640 * 480, 1024), 16u);
    EXPECT_EQ(vulkan_group_for_samples(8, 455 * 341, 1024), 8u);  // a real flight's frame: unchanged
    EXPECT_EQ(vulkan_group_for_samples(1, kVulkanMaxSamplesPerItem, 1024), 1u);
    EXPECT_EQ(vulkan_group_for_samples(1, kVulkanMaxSamplesPerItem + 1, 1024), 2u);
    EXPECT_EQ(vulkan_group_for_samples(256, 0, 1024), 256u);
    // Beyond what the largest group can walk: 0, for the backend to refuse the plan.
    EXPECT_EQ(vulkan_group_for_samples(4, kVulkanMaxSamplesPerItem * 1024, 1024), 1024u);
    EXPECT_EQ(vulkan_group_for_samples(4, kVulkanMaxSamplesPerItem * 1024 + 1, 1024), 0u);
}

TEST(NccWorkShape, OddReportsStillGiveAValidShape) {
    for (bool host : {false, true})
        for (const auto& [g, l, m] : {std::tuple<std::size_t, std::size_t, std::size_t>{0, 0, 0}, {1, 1, 1}, {3, 48, 100},
                                      {100000, 7, 1u << 30}, {1024, 0, 48 << 10}}) {
            for (const NccWorkShape& s : {choose_opencl_ncc_shape(limits(g, l, m, host)), choose_vulkan_ncc_shape(limits(g, l, m, host))}) {
                EXPECT_TRUE(is_pow2(s.group_size)) << g << " " << l << " " << m << " " << host;
                EXPECT_LE(s.group_size, std::max<std::size_t>(g, 1));
                EXPECT_LE(s.group_size, kNccMaxGroup);
                EXPECT_GE(s.particles_per_group, 1u);
            }
        }
}

}  // namespace
}  // namespace trn
