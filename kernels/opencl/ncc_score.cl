// Batched particle scoring: one work-group per particle. Every work item scores 8 samples at a
// time in float8/int8 vectors ("a tile": 8 neighbouring template pixels of one row, or 8
// consecutive sparse samples), so a CPU implementation (PoCL) runs them as AVX instructions
// without having to vectorize across work items, and a GPU runs 8 independent lanes per thread.
// Work item i takes tiles i, i + TRN_WG_SIZE, ...: neighbouring items read neighbouring template
// values (coalesced on a GPU) and a single work item walks the template row by row (sequential
// on a CPU). Sample values and sums are the exact integers of scoring.hpp: 7-bit bilinear weights,
// the map value I in 1/128 grey levels, the quantized template T (ScoringPlan::quantized); each
// work item sums TRN_CHUNK tiles of n, I and T in int lanes and the products in long lanes (an
// I*I or I*T product is up to 2^30), then one barrier and a sum over the work items in longs.
// Integer sums do not depend on the order, so any work-group size gives cpu-ref's bits. The host
// turns the sums into NCC / CC / SSD with finalize_score() (scoring_plan.hpp).
//
// The sampling is branch-free: invalid samples (outside the map, or past the end of the template
// row / sample list) read a safe map cell and add 0.
//
// A map with no-data comes with its cell mask (one bit per 2x2 cell, mask_words words per row);
// mask_words = 0: no mask (cells then points at a one-word stand-in).
//
// Per particle the host uploads 8 floats: a, b, c, d, tx, ty (pose_to_affine) and 2 unused.
// Per particle the kernel writes 6 longs: n, sum I, sum I^2, sum I*T, sum T, sum T^2.
#include "trn_common.clh"

#ifndef TRN_WG_SIZE
#define TRN_WG_SIZE 64  // work items per particle, any positive number (the build passes -D)
#endif
#ifndef TRN_CHUNK
#define TRN_CHUNK 64  // tiles per work item summed in int lanes before joining the total (<= 2^16)
#endif

typedef struct {
    float a, b, c, d, tx, ty;
} Affine;

// Per-lane sums of one work item: a chunk's part (n grows by subtracting the -1 lanes of a valid
// mask; I and T sums stay below 2^31 for TRN_CHUNK tiles) and the running total.
typedef struct {
    int8 n, sj, st;
    long8 sjj, sjt, stt;
} Sums8;

Sums8 sums8_zero(void) {
    Sums8 s = {(int8)0, (int8)0, (int8)0, (long8)0, (long8)0, (long8)0};
    return s;
}

typedef struct {
    long8 n, sj, sjj, sjt, st, stt;
} Total8;

Total8 total8_zero(void) {
    Total8 s = {(long8)0, (long8)0, (long8)0, (long8)0, (long8)0, (long8)0};
    return s;
}

void total8_add(Total8* to, const Sums8* from) {
    to->n += convert_long8(from->n);
    to->sj += convert_long8(from->sj);
    to->sjj += from->sjj;
    to->sjt += from->sjt;
    to->st += convert_long8(from->st);
    to->stt += from->stt;
}

long lanes_sum(long8 v) {
    const long4 h = v.lo + v.hi;
    const long2 q = h.lo + h.hi;
    return q.x + q.y;
}

Affine load_affine(__global const float* affines, int particle) {
    __global const float* p = affines + (size_t)particle * 8;
    Affine A = {p[0], p[1], p[2], p[3], p[4], p[5]};
    return A;
}

// Pixels p[0] and p[1] as one ushort (vload2 needs only byte alignment). Eight of them make a
// ushort8 whose bytes, read back with as_uchar16, are the pixels again in order on any device,
// and the CPU build loads each pair with one 16-bit insert instead of two 8-bit ones.
ushort pixel_pair(__global const uchar* p) {
    return as_ushort(vload2(0, p));
}

// The top and bottom pixel pairs of the 2x2 cells at (x0, y0). Offsets are 32-bit where the map
// allows (vector arithmetic); beyond 4 GiB of map each lane computes a 64-bit address.
__attribute__((always_inline)) void cell_pairs8(__global const uchar* map, int map_w, int map_h, int8 x0, int8 y0,
                                                uchar16* top, uchar16* bot) {
    __global const uchar* p[8];
    if ((ulong)map_w * (ulong)map_h <= 0xFFFFFFFFul) {
        const uint8 off = as_uint8(y0) * (uint)map_w + as_uint8(x0);
        p[0] = map + off.s0, p[1] = map + off.s1, p[2] = map + off.s2, p[3] = map + off.s3;
        p[4] = map + off.s4, p[5] = map + off.s5, p[6] = map + off.s6, p[7] = map + off.s7;
    } else {
        const size_t w = (size_t)map_w;
        p[0] = map + ((size_t)y0.s0 * w + (size_t)x0.s0), p[1] = map + ((size_t)y0.s1 * w + (size_t)x0.s1);
        p[2] = map + ((size_t)y0.s2 * w + (size_t)x0.s2), p[3] = map + ((size_t)y0.s3 * w + (size_t)x0.s3);
        p[4] = map + ((size_t)y0.s4 * w + (size_t)x0.s4), p[5] = map + ((size_t)y0.s5 * w + (size_t)x0.s5);
        p[6] = map + ((size_t)y0.s6 * w + (size_t)x0.s6), p[7] = map + ((size_t)y0.s7 * w + (size_t)x0.s7);
    }
    *top = as_uchar16((ushort8)(pixel_pair(p[0]), pixel_pair(p[1]), pixel_pair(p[2]), pixel_pair(p[3]), pixel_pair(p[4]),
                                pixel_pair(p[5]), pixel_pair(p[6]), pixel_pair(p[7])));
    *bot = as_uchar16((ushort8)(pixel_pair(p[0] + map_w), pixel_pair(p[1] + map_w), pixel_pair(p[2] + map_w),
                                pixel_pair(p[3] + map_w), pixel_pair(p[4] + map_w), pixel_pair(p[5] + map_w),
                                pixel_pair(p[6] + map_w), pixel_pair(p[7] + map_w)));
}

// 8 template values at the given indices (a gather; used only for partial tiles).
int8 gather8(__global const int* p, int8 i) {
    return (int8)(p[i.s0], p[i.s1], p[i.s2], p[i.s3], p[i.s4], p[i.s5], p[i.s6], p[i.s7]);
}

// round(f * 128) as int(f * 128 + 0.5f): fixed_point.hpp's weight(), 0..128.
int8 weight8(float8 f) { return convert_int8(f * 128.0f + 0.5f); }

// The no-data bits (trn/impl/cell_mask.hpp) of the cells at (x0, y0): -1 where the cell is valid.
int8 cell_valid8(__global const uint* cells, int words_per_row, int8 x0, int8 y0) {
    const int8 at = y0 * words_per_row + (x0 >> 5);
    const uint8 words = (uint8)(cells[at.s0], cells[at.s1], cells[at.s2], cells[at.s3], cells[at.s4], cells[at.s5],
                                cells[at.s6], cells[at.s7]);
    return -as_int8((words >> as_uint8(x0 & 31)) & 1u);
}

// Adds the samples at offsets (du, dv) from the template centre with quantized values t to s,
// skipping lanes that are outside the map, on a cell with no-data (when mask_words > 0: the
// cell mask's words per row) or not set in `use` (all bits set = use the lane).
// always_inline: PoCL would otherwise keep it a call with the sums in memory.
__attribute__((always_inline)) void add_samples8(Sums8* s, const Affine* A, float8 du, float8 dv, int8 t, int8 use,
                                                 __global const uchar* map, int map_w, int map_h,
                                                 __global const uint* cells, int mask_words) {
    // Exactly (tx + a*du) + b*dv, each operation rounded (FP_CONTRACT is off in trn_common.clh).
    const float8 px = (A->tx + A->a * du) + A->b * dv;
    const float8 py = (A->ty + A->c * du) + A->d * dv;
    int8 valid = use & (px >= 0.0f) & (py >= 0.0f) & (px <= (float)(map_w - 1)) & (py <= (float)(map_h - 1));
    // At (0, 0) for invalid lanes so that every read stays in the map.
    const float8 sx = select((float8)0.0f, px, valid), sy = select((float8)0.0f, py, valid);
    const int8 x0 = min(convert_int8(sx), map_w - 2), y0 = min(convert_int8(sy), map_h - 2);
    if (mask_words > 0) valid &= cell_valid8(cells, mask_words, x0, y0);
    const int8 wx = weight8(sx - convert_float8(x0)), wy = weight8(sy - convert_float8(y0));
    uchar16 top, bot;  // even bytes: left pixels, odd bytes: right pixels
    cell_pairs8(map, map_w, map_h, x0, y0, &top, &bot);
    const int8 upper = convert_int8(top.even) * (128 - wx) + convert_int8(top.odd) * wx;
    const int8 lower = convert_int8(bot.even) * (128 - wx) + convert_int8(bot.odd) * wx;
    const int8 j = select((int8)0, (upper * (128 - wy) + lower * wy + 64) >> 7, valid);
    const int8 tv = select((int8)0, t, valid);
    s->n -= valid;
    s->sj += j;
    s->sjj += convert_long8(j * j);
    s->sjt += convert_long8(j * tv);
    s->st += tv;
    s->stt += convert_long8(tv * tv);
}

// Adds the work items' totals in local memory and writes the particle's result.
void reduce_and_store(const Total8* mine, __global long* out, int particle, __local long* red) {
    const int lid = (int)get_local_id(0);
    red[0 * TRN_WG_SIZE + lid] = lanes_sum(mine->n);
    red[1 * TRN_WG_SIZE + lid] = lanes_sum(mine->sj);
    red[2 * TRN_WG_SIZE + lid] = lanes_sum(mine->sjj);
    red[3 * TRN_WG_SIZE + lid] = lanes_sum(mine->sjt);
    red[4 * TRN_WG_SIZE + lid] = lanes_sum(mine->st);
    red[5 * TRN_WG_SIZE + lid] = lanes_sum(mine->stt);
    barrier(CLK_LOCAL_MEM_FENCE);
    // Output word q is written by work item q mod TRN_WG_SIZE (one barrier, however small the group).
    __global long* o = out + (size_t)particle * 6;
    for (int q = lid; q < 6; q += TRN_WG_SIZE) {
        long total = 0;
        for (int i = 0; i < TRN_WG_SIZE; ++i) total += red[q * TRN_WG_SIZE + i];
        o[q] = total;
    }
}

// Every template pixel. Tile (strip s, row v) holds pixels u = 8s .. 8s+7 of row v. The tiles of
// whole strips are numbered row by row; when the width is not a multiple of 8, the partial strips
// at the rows' ends follow (the branch stays out of the main loop).
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_dense(__global const uchar* map, int map_w, int map_h, __global const uint* cells, int mask_words,
                     __global const float* affines,
                     __global const int* quantized, int templ_w, int templ_h, float cx, float cy,
                     __global long* out) {
    __local long red[6 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const int lid = (int)get_local_id(0);
    const Affine A = load_affine(affines, particle);
    const int8 lane = (int8)(0, 1, 2, 3, 4, 5, 6, 7);
    Total8 total = total8_zero();
    const int strips = templ_w / 8;
    if (strips > 0) {
        const int step_s = TRN_WG_SIZE % strips, step_v = TRN_WG_SIZE / strips;
        int s = lid % strips, v = lid / strips;
        while (v < templ_h) {
            Sums8 part = sums8_zero();
            for (int k = 0; k < TRN_CHUNK && v < templ_h; ++k) {
                const float8 du = convert_float8(s * 8 + lane) - cx, dv = (float8)((float)v - cy);
                const int8 t = vload8(s, quantized + (size_t)v * (size_t)templ_w);
                add_samples8(&part, &A, du, dv, t, (int8)(-1), map, map_w, map_h, cells, mask_words);
                s += step_s;
                v += step_v;
                if (s >= strips) s -= strips, ++v;
            }
            total8_add(&total, &part);
        }
    }
    if (strips * 8 < templ_w) {
        const int8 u = strips * 8 + lane;
        const float8 du = convert_float8(u) - cx;
        const int8 use = u < templ_w, uc = min(u, templ_w - 1);
        for (int v0 = lid; v0 < templ_h; v0 += TRN_CHUNK * TRN_WG_SIZE) {
            Sums8 part = sums8_zero();
            for (int v = v0; v < templ_h && v < v0 + TRN_CHUNK * TRN_WG_SIZE; v += TRN_WG_SIZE)
                add_samples8(&part, &A, du, (float8)((float)v - cy), gather8(quantized + (size_t)v * (size_t)templ_w, uc), use,
                             map, map_w, map_h, cells, mask_words);
            total8_add(&total, &part);
        }
    }
    reduce_and_store(&total, out, particle, red);
}

// A sparse sample set: offsets[k] = (u - cx, v - cy) of sample k, computed on the host with the
// same float operations as the dense kernel. Tile g holds samples 8g .. 8g+7; a partial last tile
// is added by work item 0.
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_sparse(__global const uchar* map, int map_w, int map_h, __global const uint* cells, int mask_words,
                      __global const float* affines,
                      __global const int* quantized, __global const float2* offsets, int count,
                      __global long* out) {
    __local long red[6 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const int lid = (int)get_local_id(0);
    const Affine A = load_affine(affines, particle);
    const int tiles = count / 8;
    __global const float* xy = (__global const float*)offsets;  // du, dv interleaved
    Total8 total = total8_zero();
    for (int g = lid; g < tiles;) {
        Sums8 part = sums8_zero();
        for (int k = 0; k < TRN_CHUNK && g < tiles; ++k, g += TRN_WG_SIZE) {
            const float16 o = vload16(g, xy);
            add_samples8(&part, &A, o.even, o.odd, vload8(g, quantized), (int8)(-1), map, map_w, map_h, cells, mask_words);
        }
        total8_add(&total, &part);
    }
    if (lid == 0 && tiles * 8 < count) {
        const int8 k = tiles * 8 + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
        const int8 kc = min(k, count - 1);
        const float2 o0 = offsets[kc.s0], o1 = offsets[kc.s1], o2 = offsets[kc.s2], o3 = offsets[kc.s3];
        const float2 o4 = offsets[kc.s4], o5 = offsets[kc.s5], o6 = offsets[kc.s6], o7 = offsets[kc.s7];
        const float8 du = (float8)(o0.x, o1.x, o2.x, o3.x, o4.x, o5.x, o6.x, o7.x);
        const float8 dv = (float8)(o0.y, o1.y, o2.y, o3.y, o4.y, o5.y, o6.y, o7.y);
        Sums8 part = sums8_zero();
        add_samples8(&part, &A, du, dv, gather8(quantized, kc), k < count, map, map_w, map_h, cells, mask_words);
        total8_add(&total, &part);
    }
    reduce_and_store(&total, out, particle, red);
}
