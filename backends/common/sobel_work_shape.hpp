#pragma once
// How the device Sobel kernels (kernels/opencl/sobel3x3.cl, kernels/vulkan/sobel3x3.comp) split
// an image into work: one work item per 16-pixel strip and block of rows, work-groups shaped from
// what the device reports about itself (never from its type). The kernels use no local/shared
// memory, so the local-memory size does not limit the shape.
#include <cstddef>

namespace trn {

inline constexpr std::size_t kSobelStripPixels = 16;  // pixels per work item along a row
inline constexpr std::size_t kSobelMaxRowsPerItem = 16;

// What a device says about how it runs work-groups for one kernel.
struct WorkGroupLimits {
    std::size_t max_group_size = 1;  // OpenCL CL_KERNEL_WORK_GROUP_SIZE; Vulkan min(maxComputeWorkGroupInvocations, maxComputeWorkGroupSize[0])
    std::size_t lanes = 1;           // OpenCL CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE; Vulkan subgroupSize
    std::size_t compute_units = 0;   // OpenCL CL_DEVICE_MAX_COMPUTE_UNITS; 0 where the API does not say (Vulkan)
    std::size_t max_group_y = 1024;  // largest work-group extent along y (Vulkan maxComputeWorkGroupSize[1])
};

struct SobelWorkShape {
    std::size_t group_x = 1, group_y = 1;  // work-group: strips x row blocks
    std::size_t rows_per_item = 1;
    std::size_t groups_x = 1, groups_y = 1;  // work-groups to launch (covering every strip and row)
};

// Work-group: `lanes` strips side by side (adjacent items read adjacent 16-byte vectors: one
// coalesced line per subgroup on a GPU) times as many row blocks as fill a group of up to 256
// items. Rows per item: as many as still leave four full work-groups per compute unit (each
// item then loads a source row once for up to 16 output rows), at least 1; with compute_units
// unknown, enough items for 64 work-groups. Every value is >= 1.
SobelWorkShape choose_sobel_work_shape(const WorkGroupLimits& limits, std::size_t width, std::size_t height);

}  // namespace trn
