// Host-side planning of the CUDA kernels; see cuda_plan.hpp.
#include "cuda_plan.hpp"

#include <algorithm>
#include <cstdint>

#include "trn/error.hpp"
#include "trn/limits.hpp"

namespace trn::cuda {
namespace {

std::size_t ceil_div(std::size_t a, std::size_t b) { return (a + b - 1) / b; }
std::string mib(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

static_assert(sizeof(TrnNccArgs) == 80 && sizeof(TrnSobelArgs) == 48, "the kernels' argument layout (trn_cuda_args.h) changed");
// 32-bit cell indices and pixel rows in the kernels: the largest map has 2^30 pixels.
static_assert(limits::kMaxMapPixels <= (std::int64_t(1) << 31), "ncc_score.cu indexes the map's cells with int");

std::size_t ncc_block_size(std::uint32_t work_group, std::size_t chosen, std::size_t kernel_max) {
    if (kernel_max < kWarp)
        throw Error("cuda: the NCC kernels allow blocks of at most " + std::to_string(kernel_max) +
                    " threads on this device, less than one warp (32), which their reduction needs");
    if (work_group != 0) {
        if ((work_group & (work_group - 1)) != 0 || work_group < kWarp || work_group > 1024)
            throw Error("BackendOptions.cuda.work_group = " + std::to_string(work_group) +
                        ": expected a power of two from 32 to 1024 (whole warps)");
        if (work_group > kernel_max)
            throw Error("BackendOptions.cuda.work_group = " + std::to_string(work_group) + ": the NCC kernels allow at most " +
                        std::to_string(kernel_max) + " threads per block on this device");
        return work_group;
    }
    return std::min(chosen, kernel_max);
}

NccLaunch plan_ncc(const ScoringPlan& plan, std::size_t particles, int map_w, int map_h, int mask_words, std::size_t block,
                   const GridLimits& grid) {
    const std::size_t samples = plan.sample_count();
    if (samples > std::size_t(INT32_MAX) || (plan.dense && std::size_t(plan.width) * std::size_t(plan.height) != samples))
        throw Error("score: " + std::to_string(samples) + " samples is beyond what the CUDA kernels index with 32-bit integers");
    if (particles == 0 || particles > grid.max_grid_x)
        throw Error("score: " + std::to_string(particles) + " poses: the CUDA kernels take 1 to " + std::to_string(grid.max_grid_x) +
                    " particles per call (one block each)");
    NccLaunch l;
    l.grid = particles;
    l.block = block;
    l.args.map_w = map_w;
    l.args.map_h = map_h;
    l.args.mask_words = mask_words;
    if (plan.dense) {
        l.args.templ_w = plan.width;
        l.args.templ_h = plan.height;
        l.args.cx = plan.cx;
        l.args.cy = plan.cy;
    } else {
        l.args.count = static_cast<std::int32_t>(samples);
        l.offsets_bytes = 2 * samples * sizeof(float);
    }
    l.affine_bytes = particles * kAffinePerParticle * sizeof(float);
    l.sums_bytes = particles * kSumsPerParticle * sizeof(std::int64_t);
    l.quantized_bytes = samples * sizeof(std::int32_t);
    return l;
}

void affines_of(const Pose* poses, std::size_t count, std::vector<float>& out) {
    out.resize(count * kAffinePerParticle);
    for (std::size_t i = 0; i < count; ++i) {
        const Affine A = pose_to_affine(poses[i]);
        float* dst = out.data() + i * kAffinePerParticle;
        dst[0] = A.a, dst[1] = A.b, dst[2] = A.c, dst[3] = A.d, dst[4] = A.tx, dst[5] = A.ty, dst[6] = 0, dst[7] = 0;
    }
}

void sample_offsets(const ScoringPlan& plan, std::vector<float>& out) {
    out.resize(2 * plan.points.size());
    for (std::size_t k = 0; k < plan.points.size(); ++k) {
        out[2 * k] = float(plan.points[k].u) - plan.cx;  // as the dense kernel's (float)u - cx
        out[2 * k + 1] = float(plan.points[k].v) - plan.cy;
    }
}

SobelLaunch plan_sobel(std::size_t width, std::size_t height, const WorkGroupLimits& limits, const GridLimits& grid) {
    SobelLaunch l;
    // Source rows: the pad, the image row, its right neighbour, the last strip's read past it; a
    // multiple of 64 bytes so every strip is an aligned 16-byte load. Outputs: whole strips.
    const std::size_t strips = ceil_div(width, TRN_SOBEL_STRIP);
    const std::size_t pitch = (TRN_SOBEL_PAD + strips * TRN_SOBEL_STRIP + 1 + 63) / 64 * 64;
    const std::size_t out_pitch = strips * TRN_SOBEL_STRIP;
    l.src_bytes = pitch * height;
    l.out_bytes = out_pitch * height * sizeof(std::int16_t);
    l.columns_block = 256;
    l.columns_grid = ceil_div(2 * height, l.columns_block);
    l.shape = choose_sobel_work_shape(limits, width, height);
    // A tall image on a device with a small grid: more rows per thread until the grid fits.
    while (l.shape.groups_y > grid.max_grid_y) {
        l.shape.rows_per_item *= 2;
        l.shape.groups_y = ceil_div(ceil_div(height, l.shape.rows_per_item), l.shape.group_y);
    }
    if (l.shape.groups_x > grid.max_grid_x)
        throw Error("sobel: image width " + std::to_string(width) + " needs " + std::to_string(l.shape.groups_x) +
                    " blocks across, more than the device's grid (" + std::to_string(grid.max_grid_x) + ")");
    l.args.width = static_cast<std::int32_t>(width);
    l.args.height = static_cast<std::int32_t>(height);
    l.args.pitch = static_cast<std::int32_t>(pitch);
    l.args.out_pitch = static_cast<std::int32_t>(out_pitch);
    l.args.rows_per_item = static_cast<std::int32_t>(l.shape.rows_per_item);
    return l;
}

void check_fits(const std::string& what, std::size_t bytes, std::size_t free_bytes, std::size_t total_bytes,
                const std::string& device) {
    if (bytes <= free_bytes) return;
    throw Error(what + " needs " + mib(bytes) + ", more than the free memory of " + device + ": " + mib(free_bytes) +
                " free of " + mib(total_bytes) + " (cuMemGetInfo)");
}

}  // namespace trn::cuda
