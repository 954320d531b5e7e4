// AVX2 row sampler (dense rows and sparse chunks), 16 samples per step. Positions in float without
// FMA (compiled with -mavx2 only: the contract wants every product and sum rounded separately).
// One 32-bit gather per 8 samples brings each sample's whole 2x2 cell from the map's vertical
// pixel pairs (MapPixels). The bilinear value as int16 multiply-adds (_mm256_madd_epi16):
// vertical pairs times (128 - wy, wy), then the two columns times (128 - wx, wx) — the same
// integer as fixed_point.hpp's row-first order, since nothing is rounded before the final shift.
// Products as multiply-adds too: the values I of 16 samples packed to int16 give sum I^2 and
// sum I*T of sample pairs in int32 lanes (each <= 2 * 32640 * 32767 < 2^31), widened to 64 bits
// once per 16 samples. The checked step (samples off the map or on no-data) tests each lane's
// position and, with a second gather, its cell's bit, and zeroes I and T where a sample is left
// out, so n, sum T and sum T^2 come from the same steps; sample_row_tiles_avx2 switches between
// the two per 32-sample tile along a row. Chosen at run time.
#include "ncc_rows.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>

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

    // The positions of samples k .. k+7 (Tail: only the lanes set in `lanes`; the others read nothing).
    template <bool Tail = false>
    void positions(int k, __m256& px, __m256& py, __m256i lanes = _mm256_setzero_si256()) const {
        auto load = [&](const float* p) { if constexpr (Tail) return _mm256_maskload_ps(p, lanes); else return _mm256_loadu_ps(p); };
        if (row.du) {  // (tx + a*du) + b*dv, each operation rounded on its own
            const __m256 du = load(row.du + k), dv = load(row.dv + k);
            px = _mm256_add_ps(_mm256_add_ps(tx, _mm256_mul_ps(a, du)), _mm256_mul_ps(b, dv));
            py = _mm256_add_ps(_mm256_add_ps(ty, _mm256_mul_ps(c, du)), _mm256_mul_ps(d, dv));
        } else {
            px = _mm256_add_ps(load(row.ax + k), row.bdvs ? load(row.bdvs + k) : bdv);
            py = _mm256_add_ps(load(row.ay + k), row.ddvs ? load(row.ddvs + k) : ddv);
        }
    }

    // The values I (0..32640, int32 lanes) at positions px, py >= 0; idx = y0 * width + x0 and y0
    // of each sample's cell.
    __m256i interpolate(__m256 px, __m256 py, __m256i& idx, __m256i& yi) const {
        const __m256i xi = _mm256_min_epi32(_mm256_cvttps_epi32(px), x0max);
        yi = _mm256_min_epi32(_mm256_cvttps_epi32(py), y0max);
        const __m256i wx = weight_pairs(_mm256_sub_ps(px, _mm256_cvtepi32_ps(xi)));
        const __m256i wy = weight_pairs(_mm256_sub_ps(py, _mm256_cvtepi32_ps(yi)));
        // Pair-row y, byte 2x: index y * width + x at scale 2.
        idx = _mm256_add_epi32(_mm256_mullo_epi32(yi, width), xi);
        const __m256i cell = _mm256_i32gather_epi32(base, idx, 2);
        const __m256i left = _mm256_madd_epi16(_mm256_shuffle_epi8(cell, lo_pair), wy);   // m00*(128-wy) + m01*wy
        const __m256i right = _mm256_madd_epi16(_mm256_shuffle_epi8(cell, hi_pair), wy);  // m10*(128-wy) + m11*wy
        const __m256i cols = _mm256_or_si256(left, _mm256_slli_epi32(right, 16));         // both <= 32640
        return _mm256_srai_epi32(_mm256_add_epi32(_mm256_madd_epi16(cols, wx), round), fixed::kWeightBits);
    }

    // The values I (0..32640, int32 lanes) of samples k .. k+7, all inside the map.
    __m256i values(int k) const {
        __m256 px, py;
        positions(k, px, py);
        __m256i idx, yi;
        return interpolate(px, py, idx, yi);
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
    // 8 more, then the last 1..7 (lanes past the end read nothing, sit at (0, 0) and add 0): the
    // upper int16 of each I is 0, so madd is a plain product.
    auto add8 = [&](__m256i j, __m256i t) {
        sj = _mm256_add_epi32(sj, j);
        const __m256i jj = _mm256_madd_epi16(j, j);
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_and_si256(jj, low32));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_srli_epi64(jj, 32));
        add_signed64(sjt_even, sjt_odd, _mm256_madd_epi16(j, t));
    };
    if (k + 8 <= row.count) {
        add8(s.values(k), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k)));
        k += 8;
    }
    if (k < row.count) {
        const __m256i lanes = _mm256_cmpgt_epi32(_mm256_set1_epi32(row.count - k), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        __m256 px, py;
        s.positions<true>(k, px, py, lanes);
        px = _mm256_and_ps(px, _mm256_castsi256_ps(lanes));
        py = _mm256_and_ps(py, _mm256_castsi256_ps(lanes));
        __m256i idx, yi;
        add8(_mm256_and_si256(s.interpolate(px, py, idx, yi), lanes), _mm256_maskload_epi32(row.t + k, lanes));
    }
    RowSums r;
    r.sj = hsum32(sj);
    r.sjj = hsum64(_mm256_add_epi64(sjj_even, sjj_odd));
    r.sjt = hsum64(_mm256_add_epi64(sjt_even, sjt_odd));
    return r;
}

namespace {

// Eight samples of the checked sampler: the values I and the template values T, both 0 where the
// sample is left out, and `used` = -1 where it counts.
struct Checked8 {
    __m256i j, t, used;
};

// sample_row_checked in lanes: a sample counts when its rounded position is on the map (the same
// comparisons; OnMap: known, not tested) and, on a map with no-data (Masked), its cell's bit is
// set; the position is clamped to the map first, as there, so every load stays in bounds. Tail:
// only lanes < `rest` exist.
template <bool Masked>
struct CheckedSampler : Sampler {
    const std::uint32_t* bits;
    __m256 zero_ps, xmax, ymax;

    CheckedSampler(const MapPixels& m, const RowInput& r)
        : Sampler(m, r), bits(m.cell_bits), zero_ps(_mm256_setzero_ps()), xmax(_mm256_set1_ps(float(m.width - 1))),
          ymax(_mm256_set1_ps(float(m.height - 1))) {}

    template <bool OnMap, bool Tail>
    Checked8 at(int k, int rest = 8) const {
        const __m256i lanes = _mm256_cmpgt_epi32(_mm256_set1_epi32(rest), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        __m256 px, py;
        positions<Tail>(k, px, py, lanes);
        __m256i used = _mm256_set1_epi32(-1);
        if constexpr (!OnMap) {
            // px >= 0 && py >= 0 && px <= xmax && py <= ymax, false for NaN like the scalar test.
            const __m256 on = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(px, zero_ps, _CMP_GE_OQ), _mm256_cmp_ps(py, zero_ps, _CMP_GE_OQ)),
                                            _mm256_and_ps(_mm256_cmp_ps(px, xmax, _CMP_LE_OQ), _mm256_cmp_ps(py, ymax, _CMP_LE_OQ)));
            used = _mm256_castps_si256(on);
            // Clamped (max_ps gives its second operand for NaN): the lanes on the map keep their
            // position (-0 becomes +0: the same cell and weights), the others are left out below.
            px = _mm256_min_ps(_mm256_max_ps(px, zero_ps), xmax);
            py = _mm256_min_ps(_mm256_max_ps(py, zero_ps), ymax);
        } else if constexpr (Tail) {  // lanes past the end: position (0, 0), left out below
            px = _mm256_and_ps(px, _mm256_castsi256_ps(lanes));
            py = _mm256_and_ps(py, _mm256_castsi256_ps(lanes));
        }
        __m256i idx, yi;
        const __m256i j = interpolate(px, py, idx, yi);
        if constexpr (Masked) {  // cell bit y0 * (width - 1) + x0 = idx - y0
            const __m256i bit = _mm256_sub_epi32(idx, yi);
            const __m256i word = _mm256_i32gather_epi32(reinterpret_cast<const int*>(bits), _mm256_srli_epi32(bit, 5), 4);
            const __m256i set = _mm256_and_si256(_mm256_srlv_epi32(word, _mm256_and_si256(bit, _mm256_set1_epi32(31))), _mm256_set1_epi32(1));
            used = _mm256_and_si256(used, _mm256_cmpeq_epi32(set, _mm256_set1_epi32(1)));
        }
        if constexpr (Tail) used = _mm256_and_si256(used, lanes);
        __m256i t;
        if constexpr (Tail)
            t = _mm256_maskload_epi32(row.t + k, lanes);
        else
            t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k));
        return {_mm256_and_si256(j, used), _mm256_and_si256(t, used), used};
    }
};

// The sums of sample_row_checked in lanes; the inside sampler's (sj, sjj, sjt) plus n, st and stt.
struct CheckedSums {
    __m256i n, sj, st, sjj_even, sjj_odd, sjt_even, sjt_odd, stt_even, stt_odd;
    std::int64_t n0 = 0, st0 = 0, stt0 = 0;  // added whole (the unchecked stretches' template sums)

    CheckedSums() { n = sj = st = sjj_even = sjj_odd = sjt_even = sjt_odd = stt_even = stt_odd = _mm256_setzero_si256(); }

    // Two groups of 8 (any pairing of samples serves a sum): the same int16 multiply-adds as the
    // inside sampler, and T^2 likewise (a pair <= 2 * 32767^2 < 2^31).
    void add(const Checked8& g0, const Checked8& g1) {
        const __m256i low32 = _mm256_set1_epi64x(0xFFFFFFFF);
        n = _mm256_sub_epi32(n, _mm256_add_epi32(g0.used, g1.used));
        sj = _mm256_add_epi32(sj, _mm256_add_epi32(g0.j, g1.j));  // <= 32640 per sample: no overflow within a row or chunk
        st = _mm256_add_epi32(st, _mm256_add_epi32(g0.t, g1.t));  // |T| <= 32767 likewise
        const __m256i j16 = _mm256_packs_epi32(g0.j, g1.j), t16 = _mm256_packs_epi32(g0.t, g1.t);
        const __m256i jj = _mm256_madd_epi16(j16, j16), tt = _mm256_madd_epi16(t16, t16);  // non-negative
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_and_si256(jj, low32));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_srli_epi64(jj, 32));
        stt_even = _mm256_add_epi64(stt_even, _mm256_and_si256(tt, low32));
        stt_odd = _mm256_add_epi64(stt_odd, _mm256_srli_epi64(tt, 32));
        add_signed64(sjt_even, sjt_odd, _mm256_madd_epi16(j16, t16));
    }
    // 16 samples all counted (the inside sampler's step): only sj, sjj, sjt.
    void add_inside(__m256i j0, __m256i j1, __m256i t0, __m256i t1) {
        const __m256i low32 = _mm256_set1_epi64x(0xFFFFFFFF);
        sj = _mm256_add_epi32(sj, _mm256_add_epi32(j0, j1));
        const __m256i j16 = _mm256_packs_epi32(j0, j1), t16 = _mm256_packs_epi32(t0, t1);
        const __m256i jj = _mm256_madd_epi16(j16, j16);
        sjj_even = _mm256_add_epi64(sjj_even, _mm256_and_si256(jj, low32));
        sjj_odd = _mm256_add_epi64(sjj_odd, _mm256_srli_epi64(jj, 32));
        add_signed64(sjt_even, sjt_odd, _mm256_madd_epi16(j16, t16));
    }
    // Samples k .. end-1 (1 .. 15) of the checked kind OnMap.
    template <bool OnMap, bool Masked>
    void add_rest(const CheckedSampler<Masked>& s, int k, int end) {
        const int rest = end - k;
        if (rest > 8) {
            add(s.template at<OnMap, false>(k), s.template at<OnMap, true>(k + 8, rest - 8));
        } else {
            const __m256i zero = _mm256_setzero_si256();
            add(s.template at<OnMap, true>(k, rest), Checked8{zero, zero, zero});
        }
    }
    RowSums sums() const {
        RowSums r;
        r.n = n0 + hsum32(n);
        r.sj = hsum32(sj);
        r.st = st0 + hsum32(st);
        r.sjj = hsum64(_mm256_add_epi64(sjj_even, sjj_odd));
        r.sjt = hsum64(_mm256_add_epi64(sjt_even, sjt_odd));
        r.stt = stt0 + hsum64(_mm256_add_epi64(stt_even, stt_odd));
        return r;
    }
};

template <bool Masked>
RowSums sample_row_checked_lanes(const MapPixels& m, const RowInput& row) {
    const CheckedSampler<Masked> s(m, row);
    CheckedSums acc;
    int k = 0;
    for (; k + 16 <= row.count; k += 16) acc.add(s.template at<false, false>(k), s.template at<false, false>(k + 8));
    if (k < row.count) acc.add_rest<false>(s, k, row.count);
    return acc.sums();
}

}  // namespace

RowSums sample_row_checked_avx2(const MapPixels& m, const RowInput& row) {
    return m.cell_bits ? sample_row_checked_lanes<true>(m, row) : sample_row_checked_lanes<false>(m, row);
}


RowSums sample_row_tiles_avx2(const MapPixels& m, const RowInput& row, const TemplatePrefix& prefix, std::size_t first, const Tile* tiles) {
    const CheckedSampler<true> s(m, row);
    CheckedSums acc;
    auto load_t = [&](int k) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row.t + k)); };
    for (int k0 = 0; k0 < row.count; k0 += kTileCols) {
        const int k1 = std::min(k0 + kTileCols, row.count);
        int k = k0;
        switch (tiles[k0 / kTileCols]) {
            case Tile::kNoneValid: break;
            case Tile::kAllValid:
                for (; k + 16 <= k1; k += 16) acc.add_inside(s.values(k), s.values(k + 8), load_t(k), load_t(k + 8));
                acc.n0 += k - k0, acc.st0 += prefix.st[first + k] - prefix.st[first + k0], acc.stt0 += prefix.stt[first + k] - prefix.stt[first + k0];
                if (k < k1) acc.add_rest<true>(s, k, k1);  // the row's last 1..15: on the map, counted in lanes
                break;
            case Tile::kSomeOnMap:
                for (; k + 16 <= k1; k += 16) acc.add(s.at<true, false>(k), s.at<true, false>(k + 8));
                if (k < k1) acc.add_rest<true>(s, k, k1);
                break;
            case Tile::kSome:
                for (; k + 16 <= k1; k += 16) acc.add(s.at<false, false>(k), s.at<false, false>(k + 8));
                if (k < k1) acc.add_rest<false>(s, k, k1);
                break;
        }
    }
    return acc.sums();
}

}  // namespace trn::cpu
#endif  // __x86_64__: elsewhere row_kernels() never names these
