// The old cpu backend's AVX2 dense row (see old_cpu_ncc.hpp): float interpolation from two 32-bit
// gathers per 8 samples, float sums in 8 lanes. Compiled with -mavx2 only (no FMA), as it was.
#include "old_cpu_ncc.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

namespace trn::bench::old_cpu {
namespace {

float hsum(__m256 v) {
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    s = _mm_add_ss(s, _mm_shuffle_ps(s, s, 1));
    return _mm_cvtss_f32(s);
}

}  // namespace

RowSums row_inside_avx2(const Row& r, float shift) {
    const __m256 bdv = _mm256_set1_ps(r.bdv), ddv = _mm256_set1_ps(r.ddv), vshift = _mm256_set1_ps(shift);
    const __m256i x0max = _mm256_set1_epi32(r.width - 2), y0max = _mm256_set1_epi32(r.height - 2);
    const __m256i vstride = _mm256_set1_epi32(r.stride), byte = _mm256_set1_epi32(0xFF);
    const int* base0 = reinterpret_cast<const int*>(r.map);
    const int* base1 = reinterpret_cast<const int*>(r.map + r.stride);
    __m256 sj = _mm256_setzero_ps(), sjj = sj, sjt = sj, st = sj, stt = sj;
    int k = 0;
    for (; k + 8 <= r.count; k += 8) {
        const __m256 px = _mm256_add_ps(_mm256_loadu_ps(r.ax + k), bdv);
        const __m256 py = _mm256_add_ps(_mm256_loadu_ps(r.ay + k), ddv);
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
        const __m256 t = _mm256_loadu_ps(r.t + k);
        sj = _mm256_add_ps(sj, j);
        sjj = _mm256_add_ps(sjj, _mm256_mul_ps(j, j));
        sjt = _mm256_add_ps(sjt, _mm256_mul_ps(j, t));
        st = _mm256_add_ps(st, t);
        stt = _mm256_add_ps(stt, _mm256_mul_ps(t, t));
    }
    RowSums s{float(k), hsum(sj), hsum(sjj), hsum(sjt), hsum(st), hsum(stt)};
    if (k < r.count) {  // the last < 8 samples
        Row tail = r;
        tail.ax += k, tail.ay += k, tail.t += k, tail.count -= k;
        const RowSums e = row_checked(tail, shift);
        s.n += e.n, s.sj += e.sj, s.sjj += e.sjj, s.sjt += e.sjt, s.st += e.st, s.stt += e.stt;
    }
    return s;
}

}  // namespace trn::bench::old_cpu
#else
namespace trn::bench::old_cpu {
RowSums row_inside_avx2(const Row& r, float shift) { return row_checked(r, shift); }
}  // namespace trn::bench::old_cpu
#endif
