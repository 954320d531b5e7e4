// Batched particle scoring in CUDA: one thread block per particle (blockIdx.x), its threads taking
// samples tid, tid + blockDim.x, ... (neighbouring threads read neighbouring template values). The
// sample is the exact integer definition of trn/fixed_point.hpp and trn/scoring.hpp, the same as
// kernels/opencl/ncc_score.cl: positions (tx + a*du) + b*dv with every product and sum rounded on
// its own (__fmul_rn / __fadd_rn are never contracted into FMA, and the build passes -fmad=false
// as well), 7-bit weights, the map value I in 1/128 grey levels, and 64-bit integer sums of n, I,
// I^2, I*T, T, T^2, which do not depend on the order, so any block size gives cpu-ref's bits. The
// host turns the sums into scores (finalize_score).
//
// A sample off the map, or on a cell whose no-data bit is clear (mask_words > 0), adds nothing.
// blockDim.x must be a multiple of 32 and at most 1024 (the host's shape rule guarantees it): the
// reduction sums each warp with shuffles, then the warps' totals in shared memory.
#include "trn_cuda_args.h"

namespace {

struct Sums {
    long long n, sj, sjj, sjt, st, stt;
};

struct Affine {
    float a, b, c, d, tx, ty;
};

__device__ __forceinline__ Affine load_affine(const TrnNccArgs& args) {
    const float4* p = reinterpret_cast<const float4*>(args.affines) + 2 * static_cast<size_t>(blockIdx.x);
    const float4 lo = __ldg(p), hi = __ldg(p + 1);
    return {lo.x, lo.y, lo.z, lo.w, hi.x, hi.y};
}

// round(f * 128) as int(f * 128 + 0.5f): fixed::weight, 0..128 for 0 <= f <= 1.
__device__ __forceinline__ int weight(float f) { return __float2int_rz(__fadd_rn(__fmul_rn(f, 128.0f), 0.5f)); }

// Adds the sample at offset (du, dv) from the template centre, template value t, when it is valid.
__device__ __forceinline__ void add_sample(Sums& s, const Affine& A, float du, float dv, int t, const TrnNccArgs& args) {
    const float px = __fadd_rn(__fadd_rn(A.tx, __fmul_rn(A.a, du)), __fmul_rn(A.b, dv));
    const float py = __fadd_rn(__fadd_rn(A.ty, __fmul_rn(A.c, du)), __fmul_rn(A.d, dv));
    // Written as a negation so that NaN positions are off the map, as in cpu-ref.
    if (!(px >= 0.0f && py >= 0.0f && px <= static_cast<float>(args.map_w - 1) && py <= static_cast<float>(args.map_h - 1)))
        return;
    // px >= 0: truncation is floor; the right and bottom edges reuse the last cell.
    const int x0 = min(__float2int_rz(px), args.map_w - 2), y0 = min(__float2int_rz(py), args.map_h - 2);
    if (args.mask_words > 0) {
        const unsigned int* cells = reinterpret_cast<const unsigned int*>(args.cells);
        const unsigned int word = __ldg(cells + static_cast<size_t>(y0) * args.mask_words + (x0 >> 5));
        if (((word >> (x0 & 31)) & 1u) == 0u) return;
    }
    const int wx = weight(__fsub_rn(px, static_cast<float>(x0))), wy = weight(__fsub_rn(py, static_cast<float>(y0)));
    const unsigned char* p = reinterpret_cast<const unsigned char*>(args.map) + static_cast<size_t>(y0) * args.map_w + x0;
    const int m00 = __ldg(p), m10 = __ldg(p + 1), m01 = __ldg(p + args.map_w), m11 = __ldg(p + args.map_w + 1);
    const int top = m00 * (128 - wx) + m10 * wx, bot = m01 * (128 - wx) + m11 * wx;
    const int j = (top * (128 - wy) + bot * wy + 64) >> 7;  // 0..32640
    // j*j, j*t and t*t are below 2^31 (|t| <= 32767); their sums need 64 bits.
    s.n += 1;
    s.sj += j;
    s.sjj += j * j;
    s.sjt += j * t;
    s.st += t;
    s.stt += t * t;
}

__device__ __forceinline__ long long warp_sum(long long v) {
    for (int offset = 16; offset > 0; offset >>= 1) v += __shfl_down_sync(0xffffffffu, v, offset);
    return v;
}

// Sums the block's threads and writes the particle's 6 sums.
__device__ void reduce_and_store(const Sums& mine, const TrnNccArgs& args) {
    __shared__ long long red[6][TRN_NCC_MAX_WARPS];
    const int lane = threadIdx.x & 31, warp = threadIdx.x >> 5, warps = blockDim.x >> 5;
    const long long v[6] = {warp_sum(mine.n), warp_sum(mine.sj), warp_sum(mine.sjj),
                            warp_sum(mine.sjt), warp_sum(mine.st), warp_sum(mine.stt)};
    if (lane == 0)
        for (int q = 0; q < 6; ++q) red[q][warp] = v[q];
    __syncthreads();
    if (warp != 0) return;
    long long* out = reinterpret_cast<long long*>(args.sums) + 6 * static_cast<size_t>(blockIdx.x);
    for (int q = 0; q < 6; ++q) {
        const long long total = warp_sum(lane < warps ? red[q][lane] : 0);
        if (lane == 0) out[q] = total;
    }
}

}  // namespace

// Every template pixel in row-major order: sample k is pixel (k % templ_w, k / templ_w). The
// thread steps (u, v) by blockDim.x samples without a division per sample.
extern "C" __global__ void ncc_score_dense(const TrnNccArgs args) {
    const Affine A = load_affine(args);
    const int* quantized = reinterpret_cast<const int*>(args.quantized);
    const int w = args.templ_w, step_u = blockDim.x % w, step_v = blockDim.x / w;
    Sums s = {0, 0, 0, 0, 0, 0};
    int u = threadIdx.x % w, v = threadIdx.x / w;
    while (v < args.templ_h) {
        const float du = __fsub_rn(static_cast<float>(u), args.cx), dv = __fsub_rn(static_cast<float>(v), args.cy);
        add_sample(s, A, du, dv, __ldg(quantized + static_cast<size_t>(v) * w + u), args);
        u += step_u;
        v += step_v;
        if (u >= w) u -= w, ++v;
    }
    reduce_and_store(s, args);
}

// A sparse sample set: offsets[k] = (u - cx, v - cy) of sample k, computed on the host with the
// dense kernel's float operations.
extern "C" __global__ void ncc_score_sparse(const TrnNccArgs args) {
    const Affine A = load_affine(args);
    const int* quantized = reinterpret_cast<const int*>(args.quantized);
    const float2* offsets = reinterpret_cast<const float2*>(args.offsets);
    Sums s = {0, 0, 0, 0, 0, 0};
    for (int k = threadIdx.x; k < args.count; k += blockDim.x) {
        const float2 o = __ldg(offsets + k);
        add_sample(s, A, o.x, o.y, __ldg(quantized + k), args);
    }
    reduce_and_store(s, args);
}
