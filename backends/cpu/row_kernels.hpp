#pragma once
// The one place the cpu backend's inner loop is chosen (AVX2, NEON or portable): the backend and
// the row helpers of ncc_rows.hpp call whatever row_kernels() returns, so no other code asks the
// processor what it can do.
#include "ncc_rows.hpp"

namespace trn::cpu {

struct RowKernels {
    const char* name;  // "AVX2", "NEON", "portable": shown in the backend's device info
    RowSums (*inside)(const MapPixels&, const RowInput&);
    RowSums (*checked)(const MapPixels&, const RowInput&);
    // A dense row through its tiles in one pass, or nullptr: then by runs of tiles of one kind,
    // each through inside or checked (sample_row_tiles).
    RowSums (*tiles)(const MapPixels&, const RowInput&, const TemplatePrefix&, std::size_t first, const Tile*);
    // Sparse chunks: the loop reads du, dv and the affine of RowInput (positions in registers)
    // instead of precomputed ax, ay, bdvs, ddvs.
    bool sparse_from_affine;
};

// The fastest loop this processor runs, or the portable one when `simd` is false
// (BackendOptions::Cpu::simd; TRN_CPU_SIMD=off in the programs).
const RowKernels& row_kernels(bool simd);

}  // namespace trn::cpu
