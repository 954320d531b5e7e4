#version 450
// Batched NCC / CC / SSD sums: each work-group scores PARTICLES_PER_GROUP particle poses.
//
// Each invocation walks the template samples with a stride of the work-group size. It works out a
// sample's offset (du, dv) from its template pixel index (dense plans: the sample index itself;
// sparse plans: read from the table), reads the quantized template value T once, and uses both for
// every particle of its group: it maps the sample through the pose's affine (computed on the
// host), samples the map with the integer bilinear rule of scoring.hpp (7-bit weights, the value I
// in 1/128 grey levels) and accumulates n, sum I, sum I^2, sum I*T, sum T, sum T^2 over the valid
// samples, exactly: 64-bit sums as pairs of uint32 with carries (shaderInt64 is optional, e.g. on
// Mali), 32-bit runs where they cannot overflow. The work-group then adds the sums, as many per
// round as 16 KiB of shared memory holds (subgroup arithmetic on 16-bit pieces when
// TRN_SUBGROUP_REDUCE is defined, a shared-memory tree otherwise); integer sums do not depend on
// the order, so every device and group shape gives cpu-ref's bits. The host turns the sums into scores (finalize_score).
//
// Why it is shaped this way: on lavapipe every storage-buffer read at a per-invocation address
// costs a scalar loop over the SIMD lanes, so the kernel keeps such reads few: the template value
// is read once for several particles, and the map is read by one texel fetch per sample (a 32-bit
// word with the whole 2x2 bilinear footprint). Several particles per group also give the CPU longer
// straight-line work. On GPUs the host picks one particle per group and large groups.
//
// Map layouts (specialization constant QUAD_MAP), each in up to TRN_MAX_MAP_CHUNKS row bands so
// that a 16384^2 map fits the device's buffer limits:
//   quad (binding 4, uniform texel buffers, R32_UINT): texel y*W + x holds pixels (x, y), (x+1, y),
//         (x, y+1), (x+1, y+1) in bytes 0..3, for rows 0..H-2; band c holds quad rows [c*R, c*R + R).
//   bytes (binding 3, storage buffers): four pixels to a word, row-major; band c holds rows
//         [c*R, c*R + R] (one row of overlap, so the 2x2 footprint of any sample lies in one band).
//         Used when quads (4x the memory of bytes) would exceed kQuadMapBudget (256 MiB) or
//         need more bands than that.
// No-data (MASKED): a sample on a cell with an invalid pixel is left out like one off the map.
#extension GL_GOOGLE_include_directive : require
// texelFetch on a texture without a sampler: SPIR-V reads the texel buffer with OpImageFetch on the
// image itself (a sampled image of Dim Buffer is invalid from SPIR-V 1.6 and newer validators warn).
#extension GL_EXT_samplerless_texture_functions : require
#ifdef TRN_SUBGROUP_REDUCE
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "map_access.glsl"

#define TRN_MAX_MAP_CHUNKS 8
#define TRN_RUN 32u  // samples per invocation summed in 32 bits (I and T: <= 32 * 32767 < 2^31)

layout(constant_id = 0) const uint WORKGROUP_SIZE = 64;      // power of two
layout(constant_id = 1) const uint SAMPLE_COUNT = 1;         // template samples in the plan
layout(constant_id = 2) const uint MAP_CHUNKS = 1;           // bands the map is split into
layout(constant_id = 3) const uint PARTICLES_PER_GROUP = 1;  // P
layout(constant_id = 4) const uint TEMPLATE_WIDTH = 1;
layout(constant_id = 5) const bool DENSE = true;             // sample k is template pixel k
layout(constant_id = 6) const bool QUAD_MAP = true;
layout(constant_id = 7) const bool MASKED = false;           // the map has no-data (binding 5)
layout(local_size_x_id = 0) in;

// Quantized template values T[S] (int32 bits), then (sparse plans only) the template pixel index
// v*W+u of each sample.
layout(std430, binding = 0) readonly buffer SampleTable { uint table[]; };
layout(std430, binding = 1) readonly buffer Affines { float affines[]; };  // a b c d tx ty per particle
// Per particle six 64-bit sums as (low, high) words: n, sum I, sum I^2, sum I*T, sum T, sum T^2.
layout(std430, binding = 2) writeonly buffer Sums { uvec2 sums[]; };
layout(std430, binding = 3) readonly buffer MapChunk { uint words[]; } map_chunks[TRN_MAX_MAP_CHUNKS];  // bytes layout
layout(binding = 4) uniform utextureBuffer map_quads[TRN_MAX_MAP_CHUNKS];  // quad layout (R32_UINT)
// No-data: one bit per 2x2 cell, set where all four pixels are valid (trn/impl/cell_mask.hpp),
// mask_words words per row of cells. Read only when MASKED.
layout(std430, binding = 5) readonly buffer CellMask { uint cells[]; };

layout(push_constant) uniform Push {
    uint map_width;
    uint map_height;
    uint rows_per_chunk;  // R above
    uint particle_count;
    float cx, cy;         // template centre
    uint mask_words;      // words per row of the cell mask (MASKED)
} pc;

// Word i of band c. MAP_CHUNKS is a specialization constant, so with one band the selection folds away.
uint band_word(uint c, uint i) {
    if (MAP_CHUNKS == 1u || c == 0u) return map_chunks[0].words[i];
    if (c == 1u) return map_chunks[1].words[i];
    if (c == 2u) return map_chunks[2].words[i];
    if (c == 3u) return map_chunks[3].words[i];
    if (c == 4u) return map_chunks[4].words[i];
    if (c == 5u) return map_chunks[5].words[i];
    if (c == 6u) return map_chunks[6].words[i];
    return map_chunks[7].words[i];
}

// Quad i of band c (quad layout). A texel fetch, unlike a storage-buffer read at a per-invocation
// address, is a vector gather on lavapipe.
uint band_quad(uint c, uint i) {
    int at = int(i);
    if (MAP_CHUNKS == 1u || c == 0u) return texelFetch(map_quads[0], at).r;
    if (c == 1u) return texelFetch(map_quads[1], at).r;
    if (c == 2u) return texelFetch(map_quads[2], at).r;
    if (c == 3u) return texelFetch(map_quads[3], at).r;
    if (c == 4u) return texelFetch(map_quads[4], at).r;
    if (c == 5u) return texelFetch(map_quads[5], at).r;
    if (c == 6u) return texelFetch(map_quads[6], at).r;
    return texelFetch(map_quads[7], at).r;
}

// Byte `index` of band c (bytes layout).
uint band_byte(uint c, uint index) { return (band_word(c, index >> 2u) >> ((index & 3u) * 8u)) & 0xFFu; }

// Pixel (x, y) and its right / lower neighbours, x <= W-2, y <= H-2.
uvec4 fetch_quad(uint x, uint y) {
    uint c = MAP_CHUNKS == 1u ? 0u : y / pc.rows_per_chunk;
    uint i = (y - c * pc.rows_per_chunk) * pc.map_width + x;
    if (QUAD_MAP) {
        uint w = band_quad(c, i);
        return uvec4(w & 0xFFu, (w >> 8u) & 0xFFu, (w >> 16u) & 0xFFu, w >> 24u);
    }
    uint j = i + pc.map_width;
    return uvec4(band_byte(c, i), band_byte(c, i + 1u), band_byte(c, j), band_byte(c, j + 1u));
}

// round(f * 128) as uint(f * 128 + 0.5): fixed_point.hpp's weight(), 0..128 (f * 128 is exact, so
// contraction could not change it either).
uint weight(float f) {
    precise float s = f * 128.0 + 0.5;
    return uint(s);
}

// Map value I at (px, py) in 1/128 grey levels (fixed_point.hpp's bilinear), both inside the map.
uint map_value(float px, float py) {
    uint x0 = min(uint(px), pc.map_width - 2u);  // px >= 0, so truncation is floor
    uint y0 = min(uint(py), pc.map_height - 2u);
    precise float fx = px - float(x0);
    precise float fy = py - float(y0);
    uint wx = weight(fx), wy = weight(fy);
    uvec4 q = fetch_quad(x0, y0);
    uint top = q.x * (128u - wx) + q.y * wx;
    uint bot = q.z * (128u - wx) + q.w * wx;
    return (top * (128u - wy) + bot * wy + 64u) >> 7u;
}

// Whether the cell sampled at (px, py), both inside the map, holds only valid pixels.
bool cell_valid(float px, float py) {
    uint x0 = min(uint(px), pc.map_width - 2u);
    uint y0 = min(uint(py), pc.map_height - 2u);
    return ((cells[y0 * pc.mask_words + (x0 >> 5u)] >> (x0 & 31u)) & 1u) != 0u;
}

// 64-bit integers as (low, high) uint pairs.
uvec2 add64(uvec2 a, uvec2 b) {
    uint carry;
    uint lo = uaddCarry(a.x, b.x, carry);
    return uvec2(lo, a.y + b.y + carry);
}
uvec2 add64u(uvec2 a, uint x) { return add64(a, uvec2(x, 0u)); }
uvec2 add64s(uvec2 a, int x) { return add64(a, uvec2(uint(x), x < 0 ? 0xFFFFFFFFu : 0u)); }

#ifdef TRN_SUBGROUP_REDUCE
// Subgroup sum of 64-bit values: the low word in two 16-bit pieces (sums below 2^32 for any
// subgroup of up to 65536), the high word modulo 2^32, recombined with carries.
uvec2 subgroup_add64(uvec2 v) {
    uint lo16 = subgroupAdd(v.x & 0xFFFFu), hi16 = subgroupAdd(v.x >> 16u), hi = subgroupAdd(v.y);
    return add64(uvec2(lo16, hi), uvec2(hi16 << 16u, hi16 >> 16u));
}
#endif

// The group reduces SLOTS of its 6 * PARTICLES_PER_GROUP sums per round (two barriers a round; on
// lavapipe barriers dominate when there are many), with one 64-bit partial per slot and subgroup
// (or invocation): at most 2048 of them, 16 KiB, the least maxComputeSharedMemorySize allows.
const uint SUM_COUNT = 6u * PARTICLES_PER_GROUP;
const uint SLOTS = SUM_COUNT < 2048u / WORKGROUP_SIZE ? SUM_COUNT : 2048u / WORKGROUP_SIZE;
shared uvec2 red[SLOTS * WORKGROUP_SIZE];

void main() {
    uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    uint first = group * PARTICLES_PER_GROUP;
    if (first >= pc.particle_count) return;  // whole work-group leaves together: no barrier skipped
    uint lid = gl_LocalInvocationID.x;
    float xmax = float(pc.map_width - 1u), ymax = float(pc.map_height - 1u);

    // Per particle: affine and sums. A group's spare slots past the last particle repeat the last
    // one and are not written back.
    float a[PARTICLES_PER_GROUP], b[PARTICLES_PER_GROUP], c[PARTICLES_PER_GROUP], d[PARTICLES_PER_GROUP];
    float tx[PARTICLES_PER_GROUP], ty[PARTICLES_PER_GROUP];
    uint n[PARTICLES_PER_GROUP];
    uvec2 sj[PARTICLES_PER_GROUP], sjj[PARTICLES_PER_GROUP], sjt[PARTICLES_PER_GROUP], st[PARTICLES_PER_GROUP],
        stt[PARTICLES_PER_GROUP];
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        uint pid = min(first + p, pc.particle_count - 1u);
        a[p] = affines[6u * pid + 0u], b[p] = affines[6u * pid + 1u];
        c[p] = affines[6u * pid + 2u], d[p] = affines[6u * pid + 3u];
        tx[p] = affines[6u * pid + 4u], ty[p] = affines[6u * pid + 5u];
        n[p] = 0u;
        sj[p] = uvec2(0u), sjj[p] = uvec2(0u), sjt[p] = uvec2(0u), st[p] = uvec2(0u), stt[p] = uvec2(0u);
    }

    // Sums of I and T in 32 bits over runs of TRN_RUN samples per invocation, then into 64 bits;
    // products (up to 2^30 each) go into 64 bits at once.
    const uint run_span = WORKGROUP_SIZE * TRN_RUN;
    for (uint base = lid; base < SAMPLE_COUNT; base += run_span) {
        uint rj[PARTICLES_PER_GROUP];
        int rt[PARTICLES_PER_GROUP];
        for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) rj[p] = 0u, rt[p] = 0;
        uint end = min(SAMPLE_COUNT, base + run_span);
        for (uint k = base; k < end; k += WORKGROUP_SIZE) {
            uint pixel = DENSE ? k : table[SAMPLE_COUNT + k];
            float du = float(pixel % TEMPLATE_WIDTH) - pc.cx;
            float dv = float(pixel / TEMPLATE_WIDTH) - pc.cy;
            int t = int(table[k]);
            uint tt = uint(t * t);
            for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
                precise float px = (tx[p] + a[p] * du) + b[p] * dv;
                precise float py = (ty[p] + c[p] * du) + d[p] * dv;
                bool valid = px >= 0.0 && py >= 0.0 && px <= xmax && py <= ymax;
                // Clamped so that invalid samples still read inside the map; a valid position is unchanged.
                float qx = clamp(px, 0.0, xmax), qy = clamp(py, 0.0, ymax);
                if (MASKED) valid = valid && cell_valid(qx, qy);
                uint j = map_value(qx, qy);
                // Invalid samples add zeros (selects rather than multiplies by 0 / 1: measured faster on lavapipe).
                j = valid ? j : 0u;
                n[p] += valid ? 1u : 0u;
                rj[p] += j;
                rt[p] += valid ? t : 0;
                sjj[p] = add64u(sjj[p], j * j);
                sjt[p] = add64s(sjt[p], int(j) * t);
                stt[p] = add64u(stt[p], valid ? tt : 0u);
            }
        }
        for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
            sj[p] = add64u(sj[p], rj[p]);
            st[p] = add64s(st[p], rt[p]);
        }
    }

    // Sum q = 6p + f of this invocation (f: n, sj, sjj, sjt, st, stt of particle p).
    uvec2 mine[SUM_COUNT];
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        mine[6u * p + 0u] = uvec2(n[p], 0u);
        mine[6u * p + 1u] = sj[p];
        mine[6u * p + 2u] = sjj[p];
        mine[6u * p + 3u] = sjt[p];
        mine[6u * p + 4u] = st[p];
        mine[6u * p + 5u] = stt[p];
    }
    for (uint base = 0u; base < SUM_COUNT; base += SLOTS) {
#ifdef TRN_SUBGROUP_REDUCE
        // Subgroup sums first (the device's subgroup size, never assumed), then invocation 0 adds
        // the subgroups' results.
        for (uint s = 0u; s < SLOTS && base + s < SUM_COUNT; ++s) {
            uvec2 v = subgroup_add64(mine[base + s]);
            if (subgroupElect()) red[s * WORKGROUP_SIZE + gl_SubgroupID] = v;
        }
        barrier();
        const uint partials = gl_NumSubgroups;
#else
        // Shared-memory tree (WORKGROUP_SIZE is a power of two).
        for (uint s = 0u; s < SLOTS && base + s < SUM_COUNT; ++s) red[s * WORKGROUP_SIZE + lid] = mine[base + s];
        barrier();
        for (uint half_size = WORKGROUP_SIZE / 2u; half_size > 0u; half_size /= 2u) {
            if (lid < half_size)
                for (uint s = 0u; s < SLOTS && base + s < SUM_COUNT; ++s)
                    red[s * WORKGROUP_SIZE + lid] = add64(red[s * WORKGROUP_SIZE + lid], red[s * WORKGROUP_SIZE + lid + half_size]);
            barrier();
        }
        const uint partials = 1u;
#endif
        if (lid == 0u) {
            for (uint s = 0u; s < SLOTS && base + s < SUM_COUNT; ++s) {
                uint q = base + s, pid = first + q / 6u;
                if (pid >= pc.particle_count) continue;  // a spare slot of the last group
                uvec2 total = uvec2(0u);
                for (uint i = 0u; i < partials; ++i) total = add64(total, red[s * WORKGROUP_SIZE + i]);
                sums[6u * pid + q % 6u] = total;
            }
        }
        barrier();  // red is read before the next round writes it
    }
}
