#version 450
// Batched NCC / CC / SSD sums: one work-group per particle pose.
//
// Each invocation walks the sample table (du, dv, centred template value) with a stride of the
// work-group size, maps each sample through the pose's affine (computed on the host), samples the
// u8 map bilinearly and accumulates n, sum j, sum j^2, sum j*t, sum t, sum t^2 over the valid
// samples (j = map value - value at the pose centre). The work-group then reduces the six sums in a
// fixed order (subgroup arithmetic when TRN_SUBGROUP_REDUCE is defined, shared memory otherwise),
// so repeated calls are bit-identical. The host turns the sums into scores (finalize_score).
//
// The map is split into up to TRN_MAX_MAP_CHUNKS row bands (each a separate storage buffer, so a
// 16384^2 map fits under maxStorageBufferRange); band c holds rows [c*R, c*R + R] (one row of
// overlap), so the 2x2 bilinear footprint of any sample lies in one band.
#extension GL_GOOGLE_include_directive : require
#ifdef TRN_SUBGROUP_REDUCE
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "map_access.glsl"

#define TRN_MAX_MAP_CHUNKS 8
#define TRN_RUN 32u  // samples per invocation in one inner float run

layout(constant_id = 0) const uint WORKGROUP_SIZE = 64;   // power of two
layout(constant_id = 1) const uint SAMPLE_COUNT = 1;      // template samples in the plan
layout(constant_id = 2) const uint MAP_CHUNKS = 1;        // bands the map is split into
layout(local_size_x_id = 0) in;

layout(std430, binding = 0) readonly buffer SampleTable { float samples[]; };  // du[S] dv[S] t[S]
layout(std430, binding = 1) readonly buffer Affines { float affines[]; };      // a b c d tx ty per particle
struct GroupSums {
    uint n;
    float sj, sjj, sjt, st, stt, shift, unused;
};
layout(std430, binding = 2) writeonly buffer Sums { GroupSums sums[]; };
layout(std430, binding = 3) readonly buffer MapChunk { uint words[]; } map_chunks[TRN_MAX_MAP_CHUNKS];

layout(push_constant) uniform Push {
    uint map_width;
    uint map_height;
    uint rows_per_chunk;  // R above
    uint particle_count;
} pc;

// Pixel (x, y) and its right / lower neighbours from the band that holds rows y and y+1.
// MAP_CHUNKS is a specialization constant, so with one band the selection folds away.
vec4 fetch_quad(uint x, uint y) {
    uint c = MAP_CHUNKS == 1u ? 0u : y / pc.rows_per_chunk;
    uint i = (y - c * pc.rows_per_chunk) * pc.map_width + x;
    uint j = i + pc.map_width;
    vec4 q;
    #define TRN_QUAD_FROM(k) q = vec4(float(TRN_BYTE_OF(map_chunks[k].words, i)), float(TRN_BYTE_OF(map_chunks[k].words, i + 1u)), \
                                      float(TRN_BYTE_OF(map_chunks[k].words, j)), float(TRN_BYTE_OF(map_chunks[k].words, j + 1u)))
    if (c == 0u) TRN_QUAD_FROM(0);
    else if (c == 1u) TRN_QUAD_FROM(1);
    else if (c == 2u) TRN_QUAD_FROM(2);
    else if (c == 3u) TRN_QUAD_FROM(3);
    else if (c == 4u) TRN_QUAD_FROM(4);
    else if (c == 5u) TRN_QUAD_FROM(5);
    else if (c == 6u) TRN_QUAD_FROM(6);
    else TRN_QUAD_FROM(7);
    #undef TRN_QUAD_FROM
    return q;
}

// Bilinear map value at (px, py), both already inside [0, W-1] x [0, H-1].
float map_value(float px, float py) {
    uint x0 = min(uint(px), pc.map_width - 2u);   // px >= 0, so truncation is floor
    uint y0 = min(uint(py), pc.map_height - 2u);
    precise float fx = px - float(x0);
    precise float fy = py - float(y0);
    vec4 q = fetch_quad(x0, y0);
    return trn_bilinear(q.x, q.y, q.z, q.w, fx, fy);
}

// Per-subgroup (or per-invocation) partial sums; WORKGROUP_SIZE entries cover both reductions.
shared uint red_n[WORKGROUP_SIZE];
shared float red_f[5][WORKGROUP_SIZE];

void main() {
    uint pid = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (pid >= pc.particle_count) return;  // whole work-group leaves together: no barrier skipped
    uint lid = gl_LocalInvocationID.x;

    float a = affines[6u * pid + 0u], b = affines[6u * pid + 1u];
    float c = affines[6u * pid + 2u], d = affines[6u * pid + 3u];
    float tx = affines[6u * pid + 4u], ty = affines[6u * pid + 5u];
    float xmax = float(pc.map_width - 1u), ymax = float(pc.map_height - 1u);
    float shift = map_value(clamp(tx, 0.0, xmax), clamp(ty, 0.0, ymax));

    // Two-level float sums: short runs of TRN_RUN samples per invocation, then the runs' totals,
    // which keeps rounding error small even when one invocation covers thousands of samples.
    uint n = 0u;
    float sj = 0.0, sjj = 0.0, sjt = 0.0, st = 0.0, stt = 0.0;
    const uint run_span = WORKGROUP_SIZE * TRN_RUN;
    for (uint base = lid; base < SAMPLE_COUNT; base += run_span) {
        float rj = 0.0, rjj = 0.0, rjt = 0.0, rt = 0.0, rtt = 0.0;
        uint end = min(SAMPLE_COUNT, base + run_span);
        for (uint k = base; k < end; k += WORKGROUP_SIZE) {
            float du = samples[k];
            float dv = samples[SAMPLE_COUNT + k];
            float t = samples[2u * SAMPLE_COUNT + k];
            precise float px = (tx + a * du) + b * dv;
            precise float py = (ty + c * du) + d * dv;
            bool valid = px >= 0.0 && py >= 0.0 && px <= xmax && py <= ymax;
            // Clamped so that invalid samples still read inside the map; a valid position is unchanged.
            float j = map_value(clamp(px, 0.0, xmax), clamp(py, 0.0, ymax)) - shift;
            float w = valid ? 1.0 : 0.0;
            n += valid ? 1u : 0u;
            rj += w * j;
            rjj += w * (j * j);
            rjt += w * (j * t);
            rt += w * t;
            rtt += w * (t * t);
        }
        sj += rj;
        sjj += rjj;
        sjt += rjt;
        st += rt;
        stt += rtt;
    }

#ifdef TRN_SUBGROUP_REDUCE
    // Subgroup sums first (the device's subgroup size, never assumed), then subgroup 0's results
    // are added in subgroup order by one invocation.
    n = subgroupAdd(n);
    sj = subgroupAdd(sj);
    sjj = subgroupAdd(sjj);
    sjt = subgroupAdd(sjt);
    st = subgroupAdd(st);
    stt = subgroupAdd(stt);
    if (subgroupElect()) {
        red_n[gl_SubgroupID] = n;
        red_f[0][gl_SubgroupID] = sj;
        red_f[1][gl_SubgroupID] = sjj;
        red_f[2][gl_SubgroupID] = sjt;
        red_f[3][gl_SubgroupID] = st;
        red_f[4][gl_SubgroupID] = stt;
    }
    barrier();
    if (lid == 0u) {
        for (uint s = 1u; s < gl_NumSubgroups; ++s) {
            n += red_n[s];
            sj += red_f[0][s];
            sjj += red_f[1][s];
            sjt += red_f[2][s];
            st += red_f[3][s];
            stt += red_f[4][s];
        }
#else
    // Shared-memory tree reduction (WORKGROUP_SIZE is a power of two).
    red_n[lid] = n;
    red_f[0][lid] = sj;
    red_f[1][lid] = sjj;
    red_f[2][lid] = sjt;
    red_f[3][lid] = st;
    red_f[4][lid] = stt;
    barrier();
    for (uint half_size = WORKGROUP_SIZE / 2u; half_size > 0u; half_size /= 2u) {
        if (lid < half_size) {
            red_n[lid] += red_n[lid + half_size];
            for (int f = 0; f < 5; ++f) red_f[f][lid] += red_f[f][lid + half_size];
        }
        barrier();
    }
    if (lid == 0u) {
        n = red_n[0];
        sj = red_f[0][0];
        sjj = red_f[1][0];
        sjt = red_f[2][0];
        st = red_f[3][0];
        stt = red_f[4][0];
#endif
        sums[pid].n = n;
        sums[pid].sj = sj;
        sums[pid].sjj = sjj;
        sums[pid].sjt = sjt;
        sums[pid].st = st;
        sums[pid].stt = stt;
        sums[pid].shift = shift;
        sums[pid].unused = 0.0;
    }
}
