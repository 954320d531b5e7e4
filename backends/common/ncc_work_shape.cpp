// Work-group shapes of the device NCC kernels; see ncc_work_shape.hpp.
#include "ncc_work_shape.hpp"
#include "pow2.hpp"

#include <algorithm>

namespace trn {
namespace {

// kNccSubgroupsPerGroup subgroups of `lanes`, capped by `cap`, a power of two >= 1.
std::size_t wide_group(std::size_t lanes, std::size_t cap) {
    const std::size_t lanes_pow2 = floor_pow2(std::max<std::size_t>(lanes, 1));
    const std::size_t wanted = std::min(kNccSubgroupsPerGroup * lanes_pow2, kNccMaxGroup);
    return floor_pow2(std::clamp<std::size_t>(std::min(wanted, cap), 1, kNccMaxGroup));
}

}  // namespace

NccWorkShape choose_opencl_ncc_shape(const NccDeviceLimits& limits) {
    if (limits.local_memory_is_host_memory) return {1, 1};
    const std::size_t by_local = limits.local_memory_bytes / kOpenClReductionBytes;
    return {wide_group(limits.lanes, std::min(limits.max_group_size, by_local)), 1};
}

NccWorkShape choose_vulkan_ncc_shape(const NccDeviceLimits& limits) {
    if (limits.local_memory_is_host_memory)
        return {floor_pow2(std::clamp<std::size_t>(std::min(limits.lanes, limits.max_group_size), 1, kNccMaxGroup)),
                kVulkanHostParticles};
    return {wide_group(limits.lanes, limits.max_group_size), 1};
}

std::size_t vulkan_group_for_samples(std::size_t group, std::size_t samples, std::size_t max_group) {
    while ((samples + group - 1) / group > kVulkanMaxSamplesPerItem) {
        if (group * 2 > max_group) return 0;
        group *= 2;
    }
    return group;
}

NccWorkShape choose_cuda_ncc_shape(const NccDeviceLimits& limits) {
    const std::size_t warp = floor_pow2(std::max<std::size_t>(limits.lanes, 1));
    return {std::max(wide_group(limits.lanes, limits.max_group_size), warp), 1};
}

}  // namespace trn
