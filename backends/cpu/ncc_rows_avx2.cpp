// AVX2 row sampler (dense rows and sparse chunks): 8 samples at a time, two 32-bit gathers per 8 samples (each gather
// brings a pixel and its right neighbour). Compiled with -mavx2 only (no FMA: the contract wants
// every product and sum rounded separately), chosen at run time.
#include "ncc_rows.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>

namespace trn::cpu {
namespace {

float hsum(__m256 v) {
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    s = _mm_add_ss(s, _mm_shuffle_ps(s, s, 1));
    return _mm_cvtss_f32(s);
}

}  // namespace

RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row, float shift) {
    const __m256 bdv = _mm256_set1_ps(row.bdv), ddv = _mm256_set1_ps(row.ddv), vshift = _mm256_set1_ps(shift);
    const __m256 a = _mm256_set1_ps(row.a), b = _mm256_set1_ps(row.b), c = _mm256_set1_ps(row.c), d = _mm256_set1_ps(row.d);
    const __m256 tx = _mm256_set1_ps(row.tx), ty = _mm256_set1_ps(row.ty);
    const __m256i x0max = _mm256_set1_epi32(m.width - 2), y0max = _mm256_set1_epi32(m.height - 2);
    const __m256i vstride = _mm256_set1_epi32(static_cast<int>(m.stride)), byte = _mm256_set1_epi32(0xFF);
    const int* base0 = reinterpret_cast<const int*>(m.data);
    const int* base1 = reinterpret_cast<const int*>(m.data + m.stride);
    __m256 sj = _mm256_setzero_ps(), sjj = sj, sjt = sj, st = sj, stt = sj;
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
        const __m256 fx = _mm256_sub_ps(px, _mm256_cvtepi32_ps(xi)), fy = _mm256_sub_ps(py, _mm256_cvtepi32_ps(yi));
        const __m256i off = _mm256_add_epi32(_mm256_mullo_epi32(yi, vstride), xi);
        const __m256i g0 = _mm256_i32gather_epi32(base0, off, 1), g1 = _mm256_i32gather_epi32(base1, off, 1);
        const __m256 m00 = _mm256_cvtepi32_ps(_mm256_and_si256(g0, byte));
        const __m256 m10 = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(g0, 8), byte));
        const __m256 m01 = _mm256_cvtepi32_ps(_mm256_and_si256(g1, byte));
        const __m256 m11 = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(g1, 8), byte));
        const __m256 top = _mm256_add_ps(m00, _mm256_mul_ps(fx, _mm256_sub_ps(m10, m00)));
        const __m256 bot = _mm256_add_ps(m01, _mm256_mul_ps(fx, _mm256_sub_ps(m11, m01)));
        const __m256 j = _mm256_sub_ps(_mm256_add_ps(top, _mm256_mul_ps(fy, _mm256_sub_ps(bot, top))), vshift);
        const __m256 t = _mm256_loadu_ps(row.t + k);
        sj = _mm256_add_ps(sj, j);
        sjj = _mm256_add_ps(sjj, _mm256_mul_ps(j, j));
        sjt = _mm256_add_ps(sjt, _mm256_mul_ps(j, t));
        st = _mm256_add_ps(st, t);
        stt = _mm256_add_ps(stt, _mm256_mul_ps(t, t));
    }
    RowSums r{float(k), hsum(sj), hsum(sjj), hsum(sjt), hsum(st), hsum(stt)};
    if (k < row.count && row.du) {  // the last < 8 samples of a sparse chunk
        for (; k < row.count; ++k) {
            const float px = (row.tx + row.a * row.du[k]) + row.b * row.dv[k];
            const float py = (row.ty + row.c * row.du[k]) + row.d * row.dv[k];
            RowInput one = row;
            one.du = nullptr;
            one.ax = &px, one.ay = &py, one.bdvs = nullptr, one.ddvs = nullptr, one.bdv = 0, one.ddv = 0;
            one.t = row.t + k, one.count = 1;
            const RowSums s = sample_row_inside(m, one, shift);
            r.n += s.n, r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt, r.st += s.st, r.stt += s.stt;
        }
    } else if (k < row.count) {  // the last < 8 samples
        RowInput tail = row;
        tail.ax += k, tail.ay += k, tail.t += k, tail.count -= k;
        if (tail.bdvs) tail.bdvs += k, tail.ddvs += k;
        const RowSums s = sample_row_inside(m, tail, shift);
        r.n += s.n, r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt, r.st += s.st, r.stt += s.stt;
    }
    return r;
}

}  // namespace trn::cpu
#else
namespace trn::cpu {
RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row, float shift) { return sample_row_inside(m, row, shift); }
}  // namespace trn::cpu
#endif
