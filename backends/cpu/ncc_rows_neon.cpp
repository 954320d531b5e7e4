// NEON row sampler (AArch64), four samples per step: the same integers as the portable loop in
// ncc_rows.cpp, which also takes the last 1..3 samples of a row. Positions in float with each
// product and sum rounded on its own: GCC contracts a*b + c into a fused multiply-add on AArch64
// unless told not to, and its arm_neon.h writes vmulq_f32 / vaddq_f32 as plain vector * and +,
// so the -ffp-contract=off that cmake/TrnWarnings.cmake gives every target on every architecture
// is what keeps this file (and the positions the backend precomputes) equal to cpu-ref.
// AArch64 has no gather: each lane's 2x2 cell (four bytes of the map's pixel pairs, MapPixels) is
// loaded on its own. The bilinear value in 32-bit lanes (every term < 2^31); the sums widened to
// 64 bits every step (I^2 and I*T as 32x32 -> 64-bit multiply-accumulates), so nothing can overflow.
#include "ncc_rows.hpp"

#if defined(__aarch64__)
#include <arm_neon.h>

#include <cstring>

#include "trn/fixed_point.hpp"

namespace trn::cpu {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "a cell's four bytes are read as one little-endian word");

// Lane sums of a row; n counted in 32-bit lanes (at most the row's length each).
struct LaneSums {
    int32x4_t n = vdupq_n_s32(0);
    int64x2_t sj = vdupq_n_s64(0), sjj = sj, sjt = sj, st = sj, stt = sj;

    void add_products(int32x4_t j, int32x4_t t) {
        sj = vpadalq_s32(sj, j);
        sjj = vmlal_high_s32(vmlal_s32(sjj, vget_low_s32(j), vget_low_s32(j)), j, j);
        sjt = vmlal_high_s32(vmlal_s32(sjt, vget_low_s32(j), vget_low_s32(t)), j, t);
    }
    void add_template(uint32x4_t used, int32x4_t t) {
        n = vsubq_s32(n, vreinterpretq_s32_u32(used));  // used is -1 where the sample counts
        st = vpadalq_s32(st, t);
        stt = vmlal_high_s32(vmlal_s32(stt, vget_low_s32(t), vget_low_s32(t)), t, t);
    }
};

template <bool Checked>
RowSums sample_row_lanes(const MapPixels& m, const RowInput& row) {
    const float32x4_t zero = vdupq_n_f32(0.0f), xmax = vdupq_n_f32(float(m.width - 1)), ymax = vdupq_n_f32(float(m.height - 1));
    const float32x4_t bdv = vdupq_n_f32(row.bdv), ddv = vdupq_n_f32(row.ddv);
    const float32x4_t scale = vdupq_n_f32(float(fixed::kWeightOne)), half = vdupq_n_f32(0.5f);
    const int32x4_t x0max = vdupq_n_s32(m.width - 2), y0max = vdupq_n_s32(m.height - 2);
    const int32x4_t one = vdupq_n_s32(fixed::kWeightOne), round = vdupq_n_s32(1 << (fixed::kWeightBits - 1));
    const uint32x4_t byte = vdupq_n_u32(0xFF);
    LaneSums acc;
    int k = 0;
    for (; k + 4 <= row.count; k += 4) {
        float32x4_t px = vaddq_f32(vld1q_f32(row.ax + k), row.bdvs ? vld1q_f32(row.bdvs + k) : bdv);
        float32x4_t py = vaddq_f32(vld1q_f32(row.ay + k), row.ddvs ? vld1q_f32(row.ddvs + k) : ddv);
        uint32x4_t used = vdupq_n_u32(~0u);
        if constexpr (Checked) {
            // On the map: the portable loop's comparisons, false for NaN as there.
            used = vandq_u32(vandq_u32(vcgeq_f32(px, zero), vcgeq_f32(py, zero)), vandq_u32(vcleq_f32(px, xmax), vcleq_f32(py, ymax)));
            // Clamped so every load stays in bounds (maxnm: a NaN lane becomes 0; it is left out below).
            px = vminnmq_f32(vmaxnmq_f32(px, zero), xmax);
            py = vminnmq_f32(vmaxnmq_f32(py, zero), ymax);
        }
        // px >= 0: truncation (FCVTZS) is floor, as int() in the portable loop.
        const int32x4_t x0 = vminq_s32(vcvtq_s32_f32(px), x0max), y0 = vminq_s32(vcvtq_s32_f32(py), y0max);
        // fixed::weight: int(f * 128 + 0.5f) with f = p - x0, each step rounded on its own.
        const int32x4_t wx = vcvtq_s32_f32(vaddq_f32(vmulq_f32(vsubq_f32(px, vcvtq_f32_s32(x0)), scale), half));
        const int32x4_t wy = vcvtq_s32_f32(vaddq_f32(vmulq_f32(vsubq_f32(py, vcvtq_f32_s32(y0)), scale), half));
        alignas(16) std::int32_t xs[4], ys[4];
        alignas(16) std::uint32_t cells[4], bits[4] = {1, 1, 1, 1};
        vst1q_s32(xs, x0);
        vst1q_s32(ys, y0);
        for (int i = 0; i < 4; ++i) {
            std::memcpy(&cells[i], m.pairs + std::ptrdiff_t(ys[i]) * m.pair_stride + 2 * std::ptrdiff_t(xs[i]), 4);
            if constexpr (Checked)
                if (m.cell_bits) {  // a cell holding no-data leaves the sample out
                    const std::ptrdiff_t bit = std::ptrdiff_t(ys[i]) * (m.width - 1) + xs[i];
                    bits[i] = (m.cell_bits[bit >> 5] >> (bit & 31)) & 1u;
                }
        }
        if constexpr (Checked) used = vandq_u32(used, vceqq_u32(vld1q_u32(bits), vdupq_n_u32(1)));
        // Bytes p0..p3 of a cell: (x, y), (x, y+1), (x+1, y), (x+1, y+1); fixed::bilinear's order.
        const uint32x4_t c = vld1q_u32(cells);
        const int32x4_t p0 = vreinterpretq_s32_u32(vandq_u32(c, byte)), p1 = vreinterpretq_s32_u32(vandq_u32(vshrq_n_u32(c, 8), byte));
        const int32x4_t p2 = vreinterpretq_s32_u32(vandq_u32(vshrq_n_u32(c, 16), byte)), p3 = vreinterpretq_s32_u32(vshrq_n_u32(c, 24));
        const int32x4_t iwx = vsubq_s32(one, wx), iwy = vsubq_s32(one, wy);
        const int32x4_t top = vmlaq_s32(vmulq_s32(p0, iwx), p2, wx);  // <= 32640
        const int32x4_t bot = vmlaq_s32(vmulq_s32(p1, iwx), p3, wx);
        int32x4_t j = vshrq_n_s32(vaddq_s32(vmlaq_s32(vmulq_s32(top, iwy), bot, wy), round), fixed::kWeightBits);
        int32x4_t t = vld1q_s32(row.t + k);
        if constexpr (Checked) {
            j = vandq_s32(j, vreinterpretq_s32_u32(used));
            t = vandq_s32(t, vreinterpretq_s32_u32(used));
            acc.add_template(used, t);
        }
        acc.add_products(j, t);
    }
    RowSums r;
    r.sj = vaddvq_s64(acc.sj), r.sjj = vaddvq_s64(acc.sjj), r.sjt = vaddvq_s64(acc.sjt);
    if constexpr (Checked) r.n = vaddvq_s32(acc.n), r.st = vaddvq_s64(acc.st), r.stt = vaddvq_s64(acc.stt);
    if (k < row.count) {  // the last 1..3 samples
        RowInput rest = row;
        rest.ax += k, rest.ay += k, rest.t += k, rest.count -= k;
        if (rest.bdvs) rest.bdvs += k, rest.ddvs += k;
        const RowSums s = Checked ? sample_row_checked(m, rest) : sample_row_inside(m, rest);
        r.n += s.n, r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt, r.st += s.st, r.stt += s.stt;
    }
    return r;
}

}  // namespace

RowSums sample_row_inside_neon(const MapPixels& m, const RowInput& row) { return sample_row_lanes<false>(m, row); }
RowSums sample_row_checked_neon(const MapPixels& m, const RowInput& row) { return sample_row_lanes<true>(m, row); }

}  // namespace trn::cpu
#endif  // __aarch64__: elsewhere row_kernels() never names these
