#pragma once
// The CUDA backend's host-side planning, apart from the driver so that tests check it without a
// GPU: kernel arguments, grid and block sizes, buffer layouts and the size checks, each refusing by
// name what the kernels cannot take. Device pointers are filled in by the backend afterwards.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../common/ncc_work_shape.hpp"
#include "../common/sobel_work_shape.hpp"
#include "trn/scoring_plan.hpp"
#include "trn_cuda_args.h"

namespace trn::cuda {

inline constexpr int kSumsPerParticle = 6;    // n, sj, sjj, sjt, st, stt (ncc_score.cu)
inline constexpr int kAffinePerParticle = 8;  // a, b, c, d, tx, ty, 2 unused
inline constexpr std::size_t kWarp = 32;      // the kernels' reductions assume 32-thread warps

// What a device (and a loaded kernel) reports that the plans depend on.
struct GridLimits {
    std::size_t max_grid_x = 2147483647, max_grid_y = 65535;
};

// BackendOptions.cuda.work_group: 0 (from the device) or a power of two from 32 to 1024; returns
// the block size to use for the NCC kernels, `chosen` being the rule's choice
// (choose_cuda_ncc_shape) and `kernel_max` the smaller of the two kernels' thread limits. Throws
// trn::Error naming the option, or the kernel when it allows less than one warp.
std::size_t ncc_block_size(std::uint32_t work_group, std::size_t chosen, std::size_t kernel_max);

struct NccLaunch {
    TrnNccArgs args{};             // every scalar set, device pointers 0
    std::size_t grid = 0, block = 0;  // one block per particle
    std::size_t affine_bytes = 0, sums_bytes = 0, quantized_bytes = 0, offsets_bytes = 0;
};

// Plans one score call of `particles` poses on a map_w x map_h map (mask_words: the cell mask's
// words per row, 0 without no-data). Throws trn::Error when the counts exceed what the kernels
// index with 32-bit integers or the device's grid.
NccLaunch plan_ncc(const ScoringPlan& plan, std::size_t particles, int map_w, int map_h, int mask_words, std::size_t block,
                   const GridLimits& grid);

// The per-particle floats the kernels read (pose_to_affine), kAffinePerParticle each.
void affines_of(const Pose* poses, std::size_t count, std::vector<float>& out);
// Sparse plans: (u - cx, v - cy) per sample with the dense kernel's float operations.
void sample_offsets(const ScoringPlan& plan, std::vector<float>& out);

struct SobelLaunch {
    TrnSobelArgs args{};  // scalars set, device pointers 0
    std::size_t src_bytes = 0, out_bytes = 0;  // the padded source, each of gx and gy
    std::size_t columns_grid = 0, columns_block = 0;
    SobelWorkShape shape;  // the main kernel's blocks and grid
};

// Plans a Sobel call on a width x height image: kernels/cuda/sobel3x3.cu's layout, the shape from
// the rule file (choose_sobel_work_shape), with more rows per thread where the image is taller
// than the device's grid allows.
SobelLaunch plan_sobel(std::size_t width, std::size_t height, const WorkGroupLimits& limits, const GridLimits& grid);

// Refuses a map (or any one buffer) that does not fit the device's free memory, naming the device
// and cuMemGetInfo's figures; CUDA has no largest-allocation query, so free memory is the limit.
void check_fits(const std::string& what, std::size_t bytes, std::size_t free_bytes, std::size_t total_bytes,
                const std::string& device);

}  // namespace trn::cuda
