// AVX2 row sampler (dense rows and sparse chunks): 8 samples at a time, two 32-bit gathers per 8
// samples (each gather brings a pixel and its right neighbour). Positions in float without FMA
// (compiled with -mavx2 only: the contract wants every product and sum rounded separately); the
// bilinear interpolation as two int16 multiply-adds (_mm256_madd_epi16: pixel pairs times weight
// pairs, fixed_point.hpp); sums of I^2 and I*T as 64-bit lanes. Chosen at run time.
#include "ncc_rows.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

#include "trn/fixed_point.hpp"

namespace trn::cpu {
namespace {

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

}  // namespace

RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row) {
    const __m256 bdv = _mm256_set1_ps(row.bdv), ddv = _mm256_set1_ps(row.ddv);
    const __m256 a = _mm256_set1_ps(row.a), b = _mm256_set1_ps(row.b), c = _mm256_set1_ps(row.c), d = _mm256_set1_ps(row.d);
    const __m256 tx = _mm256_set1_ps(row.tx), ty = _mm256_set1_ps(row.ty);
    const __m256i x0max = _mm256_set1_epi32(m.width - 2), y0max = _mm256_set1_epi32(m.height - 2);
    const __m256i vstride = _mm256_set1_epi32(static_cast<int>(m.stride));
    // Bytes 0 and 1 of each 32-bit lane (a pixel and its right neighbour) to two int16.
    const __m256i spread = _mm256_setr_epi8(0, -1, 1, -1, 4, -1, 5, -1, 8, -1, 9, -1, 12, -1, 13, -1,  //
                                            0, -1, 1, -1, 4, -1, 5, -1, 8, -1, 9, -1, 12, -1, 13, -1);
    const __m256i round = _mm256_set1_epi32(1 << (fixed::kWeightBits - 1));
    const int* base0 = reinterpret_cast<const int*>(m.data);
    const int* base1 = reinterpret_cast<const int*>(m.data + m.stride);
    __m256i sj = _mm256_setzero_si256(), sjj_even = sj, sjj_odd = sj, sjt_even = sj, sjt_odd = sj;
    int k = 0;
    for (; k + 8 <= row.count; k += 8) {
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
        const __m256i off = _mm256_add_epi32(_mm256_mullo_epi32(yi, vstride), xi);
        const __m256i g0 = _mm256_i32gather_epi32(base0, off, 1), g1 = _mm256_i32gather_epi32(base1, off, 1);
        const __m256i top = _mm256_madd_epi16(_mm256_shuffle_epi8(g0, spread), wx);  // m00*(128-wx) + m10*wx
        const __m256i bot = _mm256_madd_epi16(_mm256_shuffle_epi8(g1, spread), wx);
        const __m256i pair = _mm256_or_si256(top, _mm256_slli_epi32(bot, 16));       // both <= 32640
        const __m256i j = _mm256_srai_epi32(_mm256_add_epi32(_mm256_madd_epi16(pair, wy), round), fixed::kWeightBits);
        const __m256i t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k));
        sj = _mm256_add_epi32(sj, j);  // <= 32640 per sample: no overflow within a row or chunk
        const __m256i j_odd = _mm256_srli_epi64(j, 32), t_odd = _mm256_srli_epi64(t, 32);
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_mul_epi32(j, j));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_mul_epi32(j_odd, j_odd));
        sjt_even = _mm256_add_epi64(sjt_even, _mm256_mul_epi32(j, t));
        sjt_odd = _mm256_add_epi64(sjt_odd, _mm256_mul_epi32(j_odd, t_odd));
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
