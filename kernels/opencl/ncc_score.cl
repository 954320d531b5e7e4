// Batched particle scoring: one work-group per particle. Every work item scores 8 samples at a
// time in float8/int8 vectors ("a tile": 8 neighbouring template pixels of one row, or 8
// consecutive sparse samples), so a CPU implementation (PoCL) runs them as AVX instructions
// without having to vectorize across work items, and a GPU runs 8 independent lanes per thread.
// Work item i takes tiles i, i + TRN_WG_SIZE, ...: neighbouring items read neighbouring template
// values (coalesced on a GPU) and a single work item walks the template row by row (sequential
// on a CPU). Each work item sums TRN_CHUNK tiles in float before joining its running total, which
// keeps the float error of long templates small; then one barrier and a fixed-order sum over the
// work items (repeated calls are bit-identical). The host turns the sums into NCC / CC / SSD with
// finalize_score() (scoring_plan.hpp).
//
// The sampling is branch-free: invalid samples (outside the map, or past the end of the template
// row / sample list) read a safe map cell and add 0, and adding 0 leaves a float sum unchanged.
//
// Per particle the host uploads 8 floats: a, b, c, d, tx, ty (pose_to_affine) and 2 unused.
// Per particle the kernel writes 8 uints: n, then the float bits of sj, sjj, sjt, st, stt, shift.
#include "trn_common.clh"

#ifndef TRN_WG_SIZE
#define TRN_WG_SIZE 64  // work items per particle, any positive number (the build passes -D)
#endif
#ifndef TRN_CHUNK
#define TRN_CHUNK 64  // tiles per work item summed in float before joining the total
#endif

typedef struct {
    float a, b, c, d, tx, ty;
} Affine;

// Per-lane sums of one work item (n grows by subtracting the -1 lanes of a valid mask).
typedef struct {
    int8 n;
    float8 sj, sjj, sjt, st, stt;
} Sums8;

Sums8 sums8_zero(void) {
    Sums8 s = {(int8)0, (float8)0.0f, (float8)0.0f, (float8)0.0f, (float8)0.0f, (float8)0.0f};
    return s;
}

void sums8_add(Sums8* to, const Sums8* from) {
    to->n += from->n;
    to->sj += from->sj;
    to->sjj += from->sjj;
    to->sjt += from->sjt;
    to->st += from->st;
    to->stt += from->stt;
}

// The 8 lanes added pairwise in a fixed order.
float lanes_sum(float8 v) {
    const float4 h = v.lo + v.hi;
    const float2 q = h.lo + h.hi;
    return q.x + q.y;
}

Affine load_affine(__global const float* affines, int particle) {
    __global const float* p = affines + (size_t)particle * 8;
    Affine A = {p[0], p[1], p[2], p[3], p[4], p[5]};
    return A;
}

// Map value at the pose centre, clamped into the map: the shift that keeps float sums small.
float centre_value(__global const uchar* map, int map_w, int map_h, float x, float y) {
    x = clamp(x, 0.0f, (float)(map_w - 1));
    y = clamp(y, 0.0f, (float)(map_h - 1));
    return trn_bilinear(map, map_w, map_h, x, y);
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

// 8 float values at the given indices (a gather; used only for partial tiles).
float8 gather8(__global const float* p, int8 i) {
    return (float8)(p[i.s0], p[i.s1], p[i.s2], p[i.s3], p[i.s4], p[i.s5], p[i.s6], p[i.s7]);
}

// Adds the samples at offsets (du, dv) from the template centre with centred values t to s,
// skipping lanes that are outside the map or not set in `use` (all bits set = use the lane).
// always_inline: PoCL would otherwise keep it a call with the sums in memory.
__attribute__((always_inline)) void add_samples8(Sums8* s, const Affine* A, float8 du, float8 dv, float8 t, int8 use,
                                                 __global const uchar* map, int map_w, int map_h, float shift) {
    // Exactly (tx + a*du) + b*dv, each operation rounded (FP_CONTRACT is off in trn_common.clh).
    const float8 px = (A->tx + A->a * du) + A->b * dv;
    const float8 py = (A->ty + A->c * du) + A->d * dv;
    const int8 valid = use & (px >= 0.0f) & (py >= 0.0f) & (px <= (float)(map_w - 1)) & (py <= (float)(map_h - 1));
    // Bilinear as in trn_bilinear(), at (0, 0) for invalid lanes so that every read stays in the map.
    const float8 sx = select((float8)0.0f, px, valid), sy = select((float8)0.0f, py, valid);
    const int8 x0 = min(convert_int8(sx), map_w - 2), y0 = min(convert_int8(sy), map_h - 2);
    const float8 fx = sx - convert_float8(x0), fy = sy - convert_float8(y0);
    uchar16 top, bot;  // even bytes: left pixels, odd bytes: right pixels
    cell_pairs8(map, map_w, map_h, x0, y0, &top, &bot);
    const float8 m00 = convert_float8(top.even), m10 = convert_float8(top.odd);
    const float8 m01 = convert_float8(bot.even), m11 = convert_float8(bot.odd);
    const float8 upper = m00 + fx * (m10 - m00);
    const float8 lower = m01 + fx * (m11 - m01);
    const float8 j = select((float8)0.0f, (upper + fy * (lower - upper)) - shift, valid);
    const float8 tv = select((float8)0.0f, t, valid);
    s->n -= valid;
    s->sj += j;
    s->sjj += j * j;
    s->sjt += j * tv;
    s->st += tv;
    s->stt += tv * tv;
}

// Adds the work items' sums in local memory in a fixed order and writes the particle's result.
void reduce_and_store(const Sums8* mine, float shift, __global uint* out, int particle, __local uint* red_n,
                      __local float* red) {
    const int lid = (int)get_local_id(0);
    const int8 n = mine->n;
    red_n[lid] = (uint)(((n.s0 + n.s1) + (n.s2 + n.s3)) + ((n.s4 + n.s5) + (n.s6 + n.s7)));
    red[0 * TRN_WG_SIZE + lid] = lanes_sum(mine->sj);
    red[1 * TRN_WG_SIZE + lid] = lanes_sum(mine->sjj);
    red[2 * TRN_WG_SIZE + lid] = lanes_sum(mine->sjt);
    red[3 * TRN_WG_SIZE + lid] = lanes_sum(mine->st);
    red[4 * TRN_WG_SIZE + lid] = lanes_sum(mine->stt);
    barrier(CLK_LOCAL_MEM_FENCE);
    // Output word q is written by work item q mod TRN_WG_SIZE (one barrier, however small the group).
    __global uint* o = out + (size_t)particle * 8;
    for (int q = lid; q < 8; q += TRN_WG_SIZE) {
        if (q == 0) {
            uint total = 0u;
            for (int i = 0; i < TRN_WG_SIZE; ++i) total += red_n[i];
            o[0] = total;
        } else if (q <= 5) {
            float total = 0.0f;
            for (int i = 0; i < TRN_WG_SIZE; ++i) total += red[(q - 1) * TRN_WG_SIZE + i];
            o[q] = as_uint(total);
        } else {
            o[q] = q == 6 ? as_uint(shift) : 0u;
        }
    }
}

// Every template pixel. Tile (strip s, row v) holds pixels u = 8s .. 8s+7 of row v. The tiles of
// whole strips are numbered row by row; when the width is not a multiple of 8, the partial strips
// at the rows' ends follow (the branch stays out of the main loop).
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_dense(__global const uchar* map, int map_w, int map_h, __global const float* affines,
                     __global const float* centered, int templ_w, int templ_h, float cx, float cy,
                     __global uint* out) {
    __local uint red_n[TRN_WG_SIZE];
    __local float red[5 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const int lid = (int)get_local_id(0);
    const Affine A = load_affine(affines, particle);
    const float shift = centre_value(map, map_w, map_h, A.tx, A.ty);
    const int8 lane = (int8)(0, 1, 2, 3, 4, 5, 6, 7);
    Sums8 total = sums8_zero();
    const int strips = templ_w / 8;
    if (strips > 0) {
        const int step_s = TRN_WG_SIZE % strips, step_v = TRN_WG_SIZE / strips;
        int s = lid % strips, v = lid / strips;
        while (v < templ_h) {
            Sums8 part = sums8_zero();
            for (int k = 0; k < TRN_CHUNK && v < templ_h; ++k) {
                const float8 du = convert_float8(s * 8 + lane) - cx, dv = (float8)((float)v - cy);
                const float8 t = vload8(s, centered + (size_t)v * (size_t)templ_w);
                add_samples8(&part, &A, du, dv, t, (int8)(-1), map, map_w, map_h, shift);
                s += step_s;
                v += step_v;
                if (s >= strips) s -= strips, ++v;
            }
            sums8_add(&total, &part);
        }
    }
    if (strips * 8 < templ_w) {
        const int8 u = strips * 8 + lane;
        const float8 du = convert_float8(u) - cx;
        const int8 use = u < templ_w, uc = min(u, templ_w - 1);
        Sums8 part = sums8_zero();
        for (int v = lid; v < templ_h; v += TRN_WG_SIZE)
            add_samples8(&part, &A, du, (float8)((float)v - cy), gather8(centered + (size_t)v * (size_t)templ_w, uc), use, map,
                         map_w, map_h, shift);
        sums8_add(&total, &part);
    }
    reduce_and_store(&total, shift, out, particle, red_n, red);
}

// A sparse sample set: offsets[k] = (u - cx, v - cy) of sample k, computed on the host with the
// same float operations as the dense kernel. Tile g holds samples 8g .. 8g+7; a partial last tile
// is added by work item 0.
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_sparse(__global const uchar* map, int map_w, int map_h, __global const float* affines,
                      __global const float* centered, __global const float2* offsets, int count,
                      __global uint* out) {
    __local uint red_n[TRN_WG_SIZE];
    __local float red[5 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const int lid = (int)get_local_id(0);
    const Affine A = load_affine(affines, particle);
    const float shift = centre_value(map, map_w, map_h, A.tx, A.ty);
    const int tiles = count / 8;
    __global const float* xy = (__global const float*)offsets;  // du, dv interleaved
    Sums8 total = sums8_zero();
    for (int g = lid; g < tiles;) {
        Sums8 part = sums8_zero();
        for (int k = 0; k < TRN_CHUNK && g < tiles; ++k, g += TRN_WG_SIZE) {
            const float16 o = vload16(g, xy);
            add_samples8(&part, &A, o.even, o.odd, vload8(g, centered), (int8)(-1), map, map_w, map_h, shift);
        }
        sums8_add(&total, &part);
    }
    if (lid == 0 && tiles * 8 < count) {
        const int8 k = tiles * 8 + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
        const int8 kc = min(k, count - 1);
        const float2 o0 = offsets[kc.s0], o1 = offsets[kc.s1], o2 = offsets[kc.s2], o3 = offsets[kc.s3];
        const float2 o4 = offsets[kc.s4], o5 = offsets[kc.s5], o6 = offsets[kc.s6], o7 = offsets[kc.s7];
        const float8 du = (float8)(o0.x, o1.x, o2.x, o3.x, o4.x, o5.x, o6.x, o7.x);
        const float8 dv = (float8)(o0.y, o1.y, o2.y, o3.y, o4.y, o5.y, o6.y, o7.y);
        add_samples8(&total, &A, du, dv, gather8(centered, kc), k < count, map, map_w, map_h, shift);
    }
    reduce_and_store(&total, shift, out, particle, red_n, red);
}
