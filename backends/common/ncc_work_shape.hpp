#pragma once
// How the device NCC kernels (kernels/opencl/ncc_score.cl, kernels/vulkan/ncc_score.comp,
// kernels/cuda/ncc_score.cu) are
// shaped: work items per particle and particles per work-group, from what the device reports
// about itself (never from its type). Integer sums make any shape give cpu-ref's bits, so the
// rule only decides speed.
#include <cstddef>

namespace trn {

// What a device says that decides the NCC work-group shape.
struct NccDeviceLimits {
    std::size_t max_group_size = 1;      // OpenCL CL_DEVICE_MAX_WORK_GROUP_SIZE; Vulkan min(maxComputeWorkGroupInvocations, maxComputeWorkGroupSize[0]);
                                         // CUDA the kernel's CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK
    std::size_t lanes = 1;               // OpenCL CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE; Vulkan subgroupSize; CUDA warp size
    std::size_t local_memory_bytes = 0;  // OpenCL CL_DEVICE_LOCAL_MEM_SIZE; Vulkan maxComputeSharedMemorySize (CUDA: unused)
    // Local/shared memory is ordinary host memory, i.e. the implementation runs a work-group as a
    // loop on one CPU core: OpenCL CL_DEVICE_LOCAL_MEM_TYPE == CL_GLOBAL; Vulkan: every memory
    // type is device-local, host-visible, coherent and cached (the device has no memory of its own).
    bool local_memory_is_host_memory = false;
};

struct NccWorkShape {
    std::size_t group_size = 1;           // work items per group (a power of two)
    std::size_t particles_per_group = 1;  // particles one group scores (Vulkan; OpenCL always 1)
};

inline constexpr std::size_t kNccMaxGroup = 256;          // cap on work items per group
inline constexpr std::size_t kNccSubgroupsPerGroup = 8;   // subgroups per group on devices with their own local memory
inline constexpr std::size_t kOpenClReductionBytes = 48;  // ncc_score.cl: 6 longs of local memory per work item
inline constexpr std::size_t kVulkanHostParticles = 8;    // particles per group where groups run on CPU cores

// OpenCL (one particle per group). Local memory in host memory: 1 work item (the item's own
// 8-wide vectors fill the SIMD unit and the template is walked in memory order with no reduction;
// wider groups only add a loop and a reduction through memory). Otherwise kNccSubgroupsPerGroup x
// lanes items (enough subgroups to hide the map gathers' latency), at most kNccMaxGroup, the
// device's maximum and what its local memory holds for the reduction. A power of two, >= 1.
NccWorkShape choose_opencl_ncc_shape(const NccDeviceLimits& limits);

// Vulkan. Host memory: one subgroup per group (lavapipe runs a group on one thread, the subgroup
// being its SIMD width) scoring kVulkanHostParticles particles, so that each template read serves
// several particles. Otherwise kNccSubgroupsPerGroup x lanes items, at most kNccMaxGroup and the
// device's maximum, one particle per group (a batch of ~1000 particles then still gives enough
// groups to fill a GPU). The kernel's shared memory is a fixed 16 KiB, the spec's minimum, so it
// does not limit the shape. A power of two, >= 1.
NccWorkShape choose_vulkan_ncc_shape(const NccDeviceLimits& limits);

// Mesa's llvmpipe (lavapipe) ends an invocation's loops, silently, after 65535 iterations of all
// its loops together (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS): ncc_score.comp's sample loop takes
// one iteration per sample an invocation walks, so no invocation may walk more than this many
// (half the budget: the outer run loop and any loop the compiler does not unroll take the rest).
inline constexpr std::size_t kVulkanMaxSamplesPerItem = 32768;
// The largest Vulkan scoring group (the work_group option's bound): ncc_score.comp's 16 KiB of
// shared memory holds a partial per item for groups up to 2048.
inline constexpr std::size_t kVulkanMaxScoreGroup = 1024;

// The work-group size that scores a plan of `samples` samples: `group`, doubled while an item
// would walk more than kVulkanMaxSamplesPerItem samples; 0 when even `max_group` (a power of two)
// cannot keep within it.
std::size_t vulkan_group_for_samples(std::size_t group, std::size_t samples, std::size_t max_group);

// CUDA (one particle per block): kNccSubgroupsPerGroup warps, at most kNccMaxGroup and what the
// kernel allows (registers), a power of two; the kernel's warp-shuffle reduction needs whole warps,
// so the block is never below one warp (a kernel that allows less is refused by the backend). Its
// shared memory is a fixed 1.5 KiB, so shared memory does not limit the shape.
NccWorkShape choose_cuda_ncc_shape(const NccDeviceLimits& limits);

}  // namespace trn
