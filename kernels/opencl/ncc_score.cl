// Batched particle scoring: one work-group per particle. Each work item accumulates the sums of
// its share of the template samples, then a local-memory tree reduction adds the work items'
// sums in a fixed order (repeated calls are bit-identical). The host turns the sums into
// NCC / CC / SSD with finalize_score() (scoring_plan.hpp).
//
// Per particle the host uploads 8 floats: a, b, c, d, tx, ty (pose_to_affine) and 2 unused.
// Per particle the kernel writes 8 uints: n, then the float bits of sj, sjj, sjt, st, stt, shift.
#include "trn_common.clh"

#ifndef TRN_WG_SIZE
#define TRN_WG_SIZE 64  // work items per particle; a power of two (the build passes -D)
#endif
#ifndef TRN_SPARSE_CHUNK
#define TRN_SPARSE_CHUNK 16  // sparse samples per work item summed in float before joining the total
#endif

typedef struct {
    uint n;
    float sj, sjj, sjt, st, stt;
} Sums;

typedef struct {
    float a, b, c, d, tx, ty;
} Affine;

Sums sums_zero(void) {
    Sums s = {0u, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    return s;
}

void sums_add(Sums* to, const Sums* from) {
    to->n += from->n;
    to->sj += from->sj;
    to->sjj += from->sjj;
    to->sjt += from->sjt;
    to->st += from->st;
    to->stt += from->stt;
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

// One template sample at offset (du, dv) from the template centre with centred value t.
void add_sample(Sums* s, const Affine* A, float du, float dv, float t, __global const uchar* map, int map_w,
                int map_h, float shift) {
    // Exactly (tx + a*du) + b*dv, each operation rounded (FP_CONTRACT is off in trn_common.clh).
    const float px = (A->tx + A->a * du) + A->b * dv;
    const float py = (A->ty + A->c * du) + A->d * dv;
    if (px >= 0.0f && py >= 0.0f && px <= (float)(map_w - 1) && py <= (float)(map_h - 1)) {
        const float j = trn_bilinear(map, map_w, map_h, px, py) - shift;
        s->n += 1u;
        s->sj += j;
        s->sjj += j * j;
        s->sjt += j * t;
        s->st += t;
        s->stt += t * t;
    }
}

// Adds the work items' sums pairwise in local memory and writes the particle's result.
void reduce_and_store(Sums mine, float shift, __global uint* out, int particle, __local uint* red_n,
                      __local float* red) {
    const int lid = (int)get_local_id(0);
    red_n[lid] = mine.n;
    red[0 * TRN_WG_SIZE + lid] = mine.sj;
    red[1 * TRN_WG_SIZE + lid] = mine.sjj;
    red[2 * TRN_WG_SIZE + lid] = mine.sjt;
    red[3 * TRN_WG_SIZE + lid] = mine.st;
    red[4 * TRN_WG_SIZE + lid] = mine.stt;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int step = TRN_WG_SIZE / 2; step > 0; step >>= 1) {
        if (lid < step) {
            red_n[lid] += red_n[lid + step];
            for (int q = 0; q < 5; ++q) red[q * TRN_WG_SIZE + lid] += red[q * TRN_WG_SIZE + lid + step];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (lid == 0) {
        __global uint* o = out + (size_t)particle * 8;
        o[0] = red_n[0];
        for (int q = 0; q < 5; ++q) o[1 + q] = as_uint(red[q * TRN_WG_SIZE]);
        o[6] = as_uint(shift);
        o[7] = 0u;
    }
}

// Every template pixel, row by row. Work items stride along a row (neighbouring items read
// neighbouring template values); each row's partial sums join the running total separately,
// which keeps the float error of long templates small.
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_dense(__global const uchar* map, int map_w, int map_h, __global const float* affines,
                     __global const float* centered, int templ_w, int templ_h, float cx, float cy,
                     __global uint* out) {
    __local uint red_n[TRN_WG_SIZE];
    __local float red[5 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const Affine A = load_affine(affines, particle);
    const float shift = centre_value(map, map_w, map_h, A.tx, A.ty);
    Sums total = sums_zero();
    for (int v = 0; v < templ_h; ++v) {
        const float dv = (float)v - cy;
        __global const float* trow = centered + (size_t)v * (size_t)templ_w;
        Sums row = sums_zero();
        for (int u = (int)get_local_id(0); u < templ_w; u += TRN_WG_SIZE)
            add_sample(&row, &A, (float)u - cx, dv, trow[u], map, map_w, map_h, shift);
        sums_add(&total, &row);
    }
    reduce_and_store(total, shift, out, particle, red_n, red);
}

// A sparse sample set: offsets[k] = (u - cx, v - cy) of sample k, computed on the host with the
// same float operations as the dense kernel.
__kernel __attribute__((reqd_work_group_size(TRN_WG_SIZE, 1, 1)))
void ncc_score_sparse(__global const uchar* map, int map_w, int map_h, __global const float* affines,
                      __global const float* centered, __global const float2* offsets, int count,
                      __global uint* out) {
    __local uint red_n[TRN_WG_SIZE];
    __local float red[5 * TRN_WG_SIZE];
    const int particle = (int)get_group_id(0);
    const Affine A = load_affine(affines, particle);
    const float shift = centre_value(map, map_w, map_h, A.tx, A.ty);
    Sums total = sums_zero();
    for (int base = 0; base < count; base += TRN_WG_SIZE * TRN_SPARSE_CHUNK) {
        const int end = min(count, base + TRN_WG_SIZE * TRN_SPARSE_CHUNK);
        Sums part = sums_zero();
        for (int k = base + (int)get_local_id(0); k < end; k += TRN_WG_SIZE) {
            const float2 o = offsets[k];
            add_sample(&part, &A, o.x, o.y, centered[k], map, map_w, map_h, shift);
        }
        sums_add(&total, &part);
    }
    reduce_and_store(total, shift, out, particle, red_n, red);
}
