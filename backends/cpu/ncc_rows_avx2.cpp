// AVX2 row sampler (dense rows and sparse chunks), 16 samples per step. Positions in float without
// FMA (compiled with -mavx2 only: the contract wants every product and sum rounded separately).
// One 32-bit gather per 8 samples brings each sample's whole 2x2 cell from the map's vertical
// pixel pairs (MapPixels). The bilinear value as int16 multiply-adds (_mm256_madd_epi16):
// vertical pairs times (128 - wy, wy), then the two columns times (128 - wx, wx) — the same
// integer as fixed_point.hpp's row-first order, since nothing is rounded before the final shift.
// Products as multiply-adds too: the values I of 16 samples packed to int16 give sum I^2 and
// sum I*T of sample pairs in int32 lanes (each <= 2 * 32640 * 32767 < 2^31), widened to 64 bits
// once per 16 samples. Chosen at run time.
#include "ncc_rows.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

#include "trn/fixed_point.hpp"

namespace trn::cpu {
namespace {

static_assert(limits::kMaxMapPixels < (std::int64_t(1) << 31), "gather indices y * width + x are int32");
static_assert(2LL * fixed::kMaxValue * fixed::kMaxTemplate < (1LL << 31), "a pair of I*T products fits int32");

std::int64_t hsum32(__m256i v) {
    alignas(32) std::int32_t lanes[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), v);
    std::int64_t s = 0;
    for (std::int32_t x : lanes) s += x;
    return s;
}

std::int64_t hsum64(__m256i v) {
    alignas(32) std::int64_t lanes[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), v);
    return lanes[0] + lanes[1] + lanes[2] + lanes[3];
}

// (128 - w) in the low and w in the high int16 of each 32-bit lane.
__m256i weight_pairs(__m256 f) {
    const __m256i w = _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(f, _mm256_set1_ps(128.0f)), _mm256_set1_ps(0.5f)));
    return _mm256_or_si256(_mm256_sub_epi32(_mm256_set1_epi32(fixed::kWeightOne), w), _mm256_slli_epi32(w, 16));
}

// What stays the same along a row: the affine (sparse), the map and the constants.
struct Sampler {
    const RowInput& row;
    const int* base;
    __m256 bdv, ddv, a, b, c, d, tx, ty;
    __m256i x0max, y0max, width, lo_pair, hi_pair, round;

    Sampler(const MapPixels& m, const RowInput& r)
        : row(r), base(reinterpret_cast<const int*>(m.pairs)), bdv(_mm256_set1_ps(r.bdv)), ddv(_mm256_set1_ps(r.ddv)),
          a(_mm256_set1_ps(r.a)), b(_mm256_set1_ps(r.b)), c(_mm256_set1_ps(r.c)), d(_mm256_set1_ps(r.d)),
          tx(_mm256_set1_ps(r.tx)), ty(_mm256_set1_ps(r.ty)), x0max(_mm256_set1_epi32(m.width - 2)),
          y0max(_mm256_set1_epi32(m.height - 2)), width(_mm256_set1_epi32(m.width)),
          // Cell bytes m00 m01 m10 m11 -> (m00, m01) and (m10, m11) as int16 pairs.
          lo_pair(_mm256_setr_epi8(0, -1, 1, -1, 4, -1, 5, -1, 8, -1, 9, -1, 12, -1, 13, -1,  //
                                   0, -1, 1, -1, 4, -1, 5, -1, 8, -1, 9, -1, 12, -1, 13, -1)),
          hi_pair(_mm256_setr_epi8(2, -1, 3, -1, 6, -1, 7, -1, 10, -1, 11, -1, 14, -1, 15, -1,  //
                                   2, -1, 3, -1, 6, -1, 7, -1, 10, -1, 11, -1, 14, -1, 15, -1)),
          round(_mm256_set1_epi32(1 << (fixed::kWeightBits - 1))) {}

    // The values I (0..32640, int32 lanes) of samples k .. k+7.
    __m256i values(int k) const {
        __m256 px, py;
        if (row.du) {  // (tx + a*du) + b*dv, each operation rounded on its own
            const __m256 du = _mm256_loadu_ps(row.du + k), dv = _mm256_loadu_ps(row.dv + k);
            px = _mm256_add_ps(_mm256_add_ps(tx, _mm256_mul_ps(a, du)), _mm256_mul_ps(b, dv));
            py = _mm256_add_ps(_mm256_add_ps(ty, _mm256_mul_ps(c, du)), _mm256_mul_ps(d, dv));
        } else {
            px = _mm256_add_ps(_mm256_loadu_ps(row.ax + k), row.bdvs ? _mm256_loadu_ps(row.bdvs + k) : bdv);
            py = _mm256_add_ps(_mm256_loadu_ps(row.ay + k), row.ddvs ? _mm256_loadu_ps(row.ddvs + k) : ddv);
        }
        const __m256i xi = _mm256_min_epi32(_mm256_cvttps_epi32(px), x0max);
        const __m256i yi = _mm256_min_epi32(_mm256_cvttps_epi32(py), y0max);
        const __m256i wx = weight_pairs(_mm256_sub_ps(px, _mm256_cvtepi32_ps(xi)));
        const __m256i wy = weight_pairs(_mm256_sub_ps(py, _mm256_cvtepi32_ps(yi)));
        // Pair-row y, byte 2x: index y * width + x at scale 2.
        const __m256i cell = _mm256_i32gather_epi32(base, _mm256_add_epi32(_mm256_mullo_epi32(yi, width), xi), 2);
        const __m256i left = _mm256_madd_epi16(_mm256_shuffle_epi8(cell, lo_pair), wy);   // m00*(128-wy) + m01*wy
        const __m256i right = _mm256_madd_epi16(_mm256_shuffle_epi8(cell, hi_pair), wy);  // m10*(128-wy) + m11*wy
        const __m256i cols = _mm256_or_si256(left, _mm256_slli_epi32(right, 16));         // both <= 32640
        return _mm256_srai_epi32(_mm256_add_epi32(_mm256_madd_epi16(cols, wx), round), fixed::kWeightBits);
    }
};

// Adds the int32 lanes of v, sign-extended, to the 64-bit lanes of acc (even and odd lanes apart).
void add_signed64(__m256i& even, __m256i& odd, __m256i v) {
    const __m256i one = _mm256_set1_epi32(1);
    even = _mm256_add_epi64(even, _mm256_mul_epi32(v, one));
    odd = _mm256_add_epi64(odd, _mm256_mul_epi32(_mm256_srli_epi64(v, 32), one));
}

}  // namespace

RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row) {
    const Sampler s(m, row);
    const __m256i low32 = _mm256_set1_epi64x(0xFFFFFFFF);
    __m256i sj = _mm256_setzero_si256(), sjj_even = sj, sjj_odd = sj, sjt_even = sj, sjt_odd = sj;
    int k = 0;
    for (; k + 16 <= row.count; k += 16) {
        const __m256i j0 = s.values(k), j1 = s.values(k + 8);
        const __m256i t0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k));
        const __m256i t1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k + 8));
        sj = _mm256_add_epi32(sj, _mm256_add_epi32(j0, j1));  // <= 32640 per sample: no overflow within a row or chunk
        // Both packed alike (any pairing of samples serves a sum): int16 lanes, no saturation (|I|, |T| <= 32767).
        const __m256i j16 = _mm256_packs_epi32(j0, j1), t16 = _mm256_packs_epi32(t0, t1);
        const __m256i jj = _mm256_madd_epi16(j16, j16);  // I^2 of two samples, < 2^31: non-negative
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_and_si256(jj, low32));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_srli_epi64(jj, 32));
        add_signed64(sjt_even, sjt_odd, _mm256_madd_epi16(j16, t16));
    }
    if (k + 8 <= row.count) {  // 8 more: the upper int16 of each I is 0, so madd is a plain product
        const __m256i j = s.values(k);
        const __m256i t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k));
        sj = _mm256_add_epi32(sj, j);
        const __m256i jj = _mm256_madd_epi16(j, j);
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_and_si256(jj, low32));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_srli_epi64(jj, 32));
        add_signed64(sjt_even, sjt_odd, _mm256_madd_epi16(j, t));
        k += 8;
    }
    RowSums r;
    r.sj = hsum32(sj);
    r.sjj = hsum64(_mm256_add_epi64(sjj_even, sjj_odd));
    r.sjt = hsum64(_mm256_add_epi64(sjt_even, sjt_odd));
    auto add = [&r](const RowSums& s) { r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt; };
    if (k < row.count && row.du) {  // the last < 8 samples of a sparse chunk
        for (; k < row.count; ++k) {
            const float px = (row.tx + row.a * row.du[k]) + row.b * row.dv[k];
            const float py = (row.ty + row.c * row.du[k]) + row.d * row.dv[k];
            RowInput one = row;
            one.du = nullptr;
            one.ax = &px, one.ay = &py, one.bdvs = nullptr, one.ddvs = nullptr, one.bdv = 0, one.ddv = 0;
            one.t = row.t + k, one.count = 1;
            add(sample_row_inside(m, one));
        }
    } else if (k < row.count) {  // the last < 8 samples
        RowInput tail = row;
        tail.ax += k, tail.ay += k, tail.t += k, tail.count -= k;
        if (tail.bdvs) tail.bdvs += k, tail.ddvs += k;
        add(sample_row_inside(m, tail));
    }
    return r;
}

}  // namespace trn::cpu
#else
namespace trn::cpu {
RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row) { return sample_row_inside(m, row); }
}  // namespace trn::cpu
#endif
