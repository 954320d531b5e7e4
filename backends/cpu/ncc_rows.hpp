#pragma once
// Inner loops of the cpu backend's scoring: one template row (or chunk of sparse samples) of one
// particle. Positions follow scoring.hpp exactly: px = ax[k] + bdv with ax[k] = tx + a*du[k]
// precomputed per particle, so each product and sum is rounded as the contract says; values and
// sums are the exact integers of fixed_point.hpp.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace trn::cpu {

struct RowKernels;  // row_kernels.hpp: the inner loop this processor runs

// The no-data by blocks of 8x8 cells, to judge a rectangle of cells with four lookups: how many of
// its blocks are not all valid, and how many hold a valid cell. Summed-area tables (entry
// (by, bx) of a table of (blocks_y + 1) x (blocks_x + 1): the count over the blocks above and to
// the left) in uint16, wrapping: the difference of four entries is exact for a rectangle of fewer
// than 2^16 blocks, and larger ones are judged "some valid" (the checked sampler, always right).
struct CellBlocks {
    static constexpr int kShift = 3;
    enum Kind { kAllValid, kNoneValid, kSome };
    struct Entry {
        std::uint16_t not_full;    // blocks with an invalid cell
        std::uint16_t with_valid;  // blocks with a valid cell
    };
    int blocks_x = 0, blocks_y = 0;
    std::vector<Entry> table;  // (blocks_y + 1) x (blocks_x + 1)

    // Cells x0..x1, y0..y1 (inclusive, on the map): all valid, none valid, or some.
    Kind judge(int x0, int y0, int x1, int y1) const {
        const std::size_t bx0 = x0 >> kShift, by0 = y0 >> kShift, bx1 = (x1 >> kShift) + 1, by1 = (y1 >> kShift) + 1;
        if ((bx1 - bx0) * (by1 - by0) >= 65536) return kSome;
        const std::size_t w = std::size_t(blocks_x) + 1;
        const Entry a = table[by1 * w + bx1], b = table[by0 * w + bx1], c = table[by1 * w + bx0], d = table[by0 * w + bx0];
        if (std::uint16_t(a.not_full - b.not_full - c.not_full + d.not_full) == 0) return kAllValid;
        if (std::uint16_t(a.with_valid - b.with_valid - c.with_valid + d.with_valid) == 0) return kNoneValid;
        return kSome;
    }
};

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
    // No-data, or nullptr: one bit per cell as in trn/impl/cell_mask.hpp, but rows packed without
    // padding, so cell (x, y) is bit y * (width - 1) + x = (y * width + x) - y: the checked
    // samplers get its index from the pixel pair's, with one subtraction. At least one spare word
    // after the last. Only the checked samplers read it.
    const std::uint32_t* cell_bits = nullptr;
    const CellBlocks* blocks = nullptr;  // with cell_bits
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

// Sum of T and T^2 of the samples [k0, k1) of a plan, from its prefix sums (TemplatePrefix).
struct TemplatePrefix {
    const std::int64_t* st;   // st[k] = sum of t[0 .. k-1]; k = 0 .. samples
    const std::int64_t* stt;  // likewise t^2
};

// A dense row (one bdv, ddv) of a patch that is not all inside, on a map without no-data: the
// samples inside the map form one run, since px and py are monotonic along a row (each is one
// rounded affine step of the row's du), so only that run is sampled, by the inside sampler of
// `kernels`; the others would add nothing. T sums from `prefix` (`first`: the row's first
// sample in the plan). The same sums as sample_row_checked, n, st, stt included.
RowSums sample_row_clipped(const MapPixels& m, const RowInput& row, const RowKernels& kernels, const TemplatePrefix& prefix,
                           std::size_t first);

// A dense patch on a map with no-data, in tiles of kTileRows rows x kTileCols samples, each judged
// from the positions of its four corner samples: px and py are monotonic along a row and down a
// column (each one rounded affine step of du or dv), so every sample's position lies between the
// corners', and its cell, clamped to the map as the samplers clamp, between the corners' cells.
inline constexpr int kTileRows = 8, kTileCols = 32;
enum class Tile : std::uint8_t {
    kAllValid,   // every sample on the map and on a valid cell: the inside sampler
    kNoneValid,  // no sample on a valid cell (or none on the map): adds nothing
    kSomeOnMap,  // every sample on the map, the cells mixed: only the cells are tested
    kSome,       // some samples off the map: sample_row_checked
};
Tile judge_tile(const MapPixels& m, const float (&px)[4], const float (&py)[4]);

// One dense row of a patch through its band's tiles (`tiles`: kinds of samples [kTileCols * i,
// kTileCols * (i + 1)), neighbours of one kind sampled in one call of `kernels`, or all in its
// one-pass tiles loop). The same sums as sample_row_checked, n, st, stt included.
RowSums sample_row_tiles(const MapPixels& m, const RowInput& row, const RowKernels& kernels, const TemplatePrefix& prefix,
                         std::size_t first, const Tile* tiles);

// AVX2 versions of sample_row_inside and sample_row_checked (the same integers; interpolation and
// products as int16 multiply-adds; the checked one tests each sample's position and cell bit in
// lanes and zeroes what is left out). x86-64 only, and only through row_kernels() (which checks
// the processor has AVX2); every map the API accepts (< 2^31 pixels) fits their 32-bit gather indices.
RowSums sample_row_inside_avx2(const MapPixels& m, const RowInput& row);
RowSums sample_row_checked_avx2(const MapPixels& m, const RowInput& row);
// sample_row_tiles with AVX2, in one pass over the row (one set of lane sums for all its tiles).
RowSums sample_row_tiles_avx2(const MapPixels& m, const RowInput& row, const TemplatePrefix& prefix, std::size_t first, const Tile* tiles);

// NEON versions of sample_row_inside and sample_row_checked (AArch64 only; the same integers, four
// samples per step; dense rows and precomputed sparse positions, not RowInput's du/dv).
RowSums sample_row_inside_neon(const MapPixels& m, const RowInput& row);
RowSums sample_row_checked_neon(const MapPixels& m, const RowInput& row);

}  // namespace trn::cpu
