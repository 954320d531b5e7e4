#pragma once
// Inner loops of the cpu backend's scoring: one template row (or chunk of sparse samples) of one
// particle. Positions follow scoring.hpp exactly: px = ax[k] + bdv with ax[k] = tx + a*du[k]
// precomputed per particle, so each product and sum is rounded as the contract says; values and
// sums are the exact integers of fixed_point.hpp.
#include <cstddef>
#include <cstdint>

namespace trn::cpu {

// Exact integer sums of one row. The "inside" samplers leave n, st and stt at 0: every sample is
// valid there, so the caller takes them from the template (per-plan totals).
struct RowSums {
    std::int64_t n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
};

// The map as vertical pixel pairs: byte 2x of pair row y is pixel (x, y) and byte 2x+1 is pixel
// (x, y+1), for y = 0 .. height-2. The 2x2 cell at (x, y) is then the 4 bytes at pair row y,
// offset 2x (m00, m01, m10, m11): one 32-bit load, or one gather lane, per sample.
struct MapPixels {
    const std::uint8_t* pairs;     // (height - 1) rows of 2 * width bytes, >= 4 spare bytes after them
    std::ptrdiff_t pair_stride;    // bytes from one pair row to the next (2 * width)
    int width, height;
    // No-data (trn/impl/cell_mask.hpp's words), or nullptr: only the checked sampler reads it.
    const std::uint32_t* cell_mask = nullptr;
    std::ptrdiff_t mask_words_per_row = 0;
};

// One row of samples. Dense rows share one (bdv, ddv); sparse chunks give one per sample.
struct RowInput {
    const float* ax;    // tx + a*du per sample
    const float* ay;    // ty + c*du per sample
    float bdv, ddv;     // b*dv and d*dv for a dense row
    const float* bdvs;  // per-sample b*dv (sparse), or nullptr
    const float* ddvs;
    const std::int32_t* t;  // quantized template values (ScoringPlan::quantized)
    int count;
    // Sparse chunks on the AVX2 path: positions straight from du/dv and the affine, in registers
    // (same operations, same rounding) instead of from precomputed arrays. ax/ay unused then.
    const float* du = nullptr;
    const float* dv = nullptr;
    float a = 0, b = 0, c = 0, d = 0, tx = 0, ty = 0;
};

// Checked = samples may fall outside the map or on no-data (left out); unchecked = all known inside
// and on valid cells.
RowSums sample_row_checked(const MapPixels& m, const RowInput& row);
RowSums sample_row_inside(const MapPixels& m, const RowInput& row);

// A dense row (one bdv, ddv) of a patch that is not all inside, on a map without no-data: the
// samples inside the map form one run, since px and py are monotonic along a row (each is one
// rounded affine step of the row's du), so only that run is sampled, by the inside sampler (AVX2
// when `vector`); the others would add nothing. The same sums as sample_row_checked, n, st, stt included.
RowSums sample_row_clipped(const MapPixels& m, const RowInput& row, bool vector);

// AVX2 version of sample_row_inside (the same integers; interpolation and products as int16
// multiply-adds). Only call when avx2_available(); every map the API accepts (< 2^31 pixels) fits
// its 32-bit gather indices.
RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row);
bool avx2_available();

}  // namespace trn::cpu
