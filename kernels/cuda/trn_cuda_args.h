// The arguments of the trnkit CUDA kernels, one struct per kernel passed by value: the host
// (backends/cuda) fills the very declaration the kernel reads, so the two layouts cannot drift.
// Plain C types only: this header is compiled by nvcc for the device and by the C++ compiler for
// the host, where device pointers are CUdeviceptr values (64-bit integers).
#ifndef TRN_CUDA_ARGS_H
#define TRN_CUDA_ARGS_H

#include <stdint.h>

// ncc_score.cu: ncc_score_dense / ncc_score_sparse, one thread block per particle.
struct TrnNccArgs {
    uint64_t map;        // map pixels, one byte each, rows packed (map_w bytes apart)
    uint64_t cells;      // the no-data cell mask (trn/impl/cell_mask.hpp), or 0 when mask_words == 0
    uint64_t affines;    // 8 floats per particle: a, b, c, d, tx, ty, 2 unused (16-byte aligned loads)
    uint64_t quantized;  // int32 per sample: ScoringPlan::quantized
    uint64_t offsets;    // sparse: (u - cx, v - cy) as 2 floats per sample; 0 for dense
    uint64_t sums;       // out: 6 int64 per particle: n, sum I, sum I^2, sum I*T, sum T, sum T^2
    int32_t map_w, map_h;
    int32_t mask_words;  // cell mask words per row; 0: no mask
    int32_t templ_w, templ_h;  // dense: the template size
    int32_t count;       // sparse: the sample count
    float cx, cy;        // dense: the template centre
};

// sobel3x3.cu: sobel3x3_columns, then sobel3x3.
struct TrnSobelArgs {
    uint64_t src;        // rows of `pitch` bytes, image row y at src + y * pitch + TRN_SOBEL_PAD
    uint64_t gx, gy;     // out: int16 rows of out_pitch elements
    int32_t width, height;
    int32_t pitch;       // a multiple of 64
    int32_t out_pitch;   // a multiple of 16
    int32_t rows_per_item;
    int32_t unused;
};

#define TRN_SOBEL_PAD 16      // bytes left of each source row; its last one holds the left neighbour
#define TRN_SOBEL_STRIP 16    // pixels per thread along a row
#define TRN_NCC_MAX_WARPS 32  // 1024 threads per block at most, in warps of 32

#endif
