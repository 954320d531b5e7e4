#version 450
// Batched NCC / CC / SSD sums: each work-group scores PARTICLES_PER_GROUP particle poses.
//
// Each invocation walks the template samples with a stride of the work-group size. It works out a
// sample's offset (du, dv) from its template pixel index (dense plans: the sample index itself;
// sparse plans: read from the table), reads the centred template value once, and uses both for
// every particle of its group: it maps the sample through the pose's affine (computed on the
// host), samples the map bilinearly and accumulates n, sum j, sum j^2, sum j*t, sum t, sum t^2 over
// the valid samples (j = map value - value at the pose centre). The work-group then reduces the six
// sums per particle in a fixed order (subgroup arithmetic when TRN_SUBGROUP_REDUCE is defined,
// shared memory otherwise), so repeated calls are bit-identical. The host turns the sums into
// scores (finalize_score).
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
#extension GL_GOOGLE_include_directive : require
#ifdef TRN_SUBGROUP_REDUCE
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "map_access.glsl"

#define TRN_MAX_MAP_CHUNKS 8
#define TRN_RUN 32u  // samples per invocation in one inner float run

layout(constant_id = 0) const uint WORKGROUP_SIZE = 64;      // power of two
layout(constant_id = 1) const uint SAMPLE_COUNT = 1;         // template samples in the plan
layout(constant_id = 2) const uint MAP_CHUNKS = 1;           // bands the map is split into
layout(constant_id = 3) const uint PARTICLES_PER_GROUP = 1;  // P
layout(constant_id = 4) const uint TEMPLATE_WIDTH = 1;
layout(constant_id = 5) const bool DENSE = true;             // sample k is template pixel k
layout(constant_id = 6) const bool QUAD_MAP = true;
layout(local_size_x_id = 0) in;

// Centred template values t[S] (float bits), then (sparse plans only) the template pixel index
// v*W+u of each sample.
layout(std430, binding = 0) readonly buffer SampleTable { uint table[]; };
layout(std430, binding = 1) readonly buffer Affines { float affines[]; };  // a b c d tx ty per particle
struct GroupSums {
    uint n;
    float sj, sjj, sjt, st, stt, shift, unused;
};
layout(std430, binding = 2) writeonly buffer Sums { GroupSums sums[]; };
layout(std430, binding = 3) readonly buffer MapChunk { uint words[]; } map_chunks[TRN_MAX_MAP_CHUNKS];  // bytes layout
layout(binding = 4) uniform usamplerBuffer map_quads[TRN_MAX_MAP_CHUNKS];  // quad layout (R32_UINT)

layout(push_constant) uniform Push {
    uint map_width;
    uint map_height;
    uint rows_per_chunk;  // R above
    uint particle_count;
    float cx, cy;         // template centre
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
vec4 fetch_quad(uint x, uint y) {
    uint c = MAP_CHUNKS == 1u ? 0u : y / pc.rows_per_chunk;
    uint i = (y - c * pc.rows_per_chunk) * pc.map_width + x;
    if (QUAD_MAP) {
        uint w = band_quad(c, i);
        return vec4(float(w & 0xFFu), float((w >> 8u) & 0xFFu), float((w >> 16u) & 0xFFu), float(w >> 24u));
    }
    uint j = i + pc.map_width;
    return vec4(float(band_byte(c, i)), float(band_byte(c, i + 1u)), float(band_byte(c, j)), float(band_byte(c, j + 1u)));
}

// Bilinear map value at (px, py), both already inside [0, W-1] x [0, H-1].
float map_value(float px, float py) {
    uint x0 = min(uint(px), pc.map_width - 2u);  // px >= 0, so truncation is floor
    uint y0 = min(uint(py), pc.map_height - 2u);
    precise float fx = px - float(x0);
    precise float fy = py - float(y0);
    vec4 q = fetch_quad(x0, y0);
    return trn_bilinear(q.x, q.y, q.z, q.w, fx, fy);
}

// Partial sums of (particle p, sum f) for each subgroup (or invocation): index (p*5 + f)*WORKGROUP_SIZE + s.
shared uint red_n[PARTICLES_PER_GROUP * WORKGROUP_SIZE];
shared float red_f[PARTICLES_PER_GROUP * 5u * WORKGROUP_SIZE];

void main() {
    uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    uint first = group * PARTICLES_PER_GROUP;
    if (first >= pc.particle_count) return;  // whole work-group leaves together: no barrier skipped
    uint lid = gl_LocalInvocationID.x;
    float xmax = float(pc.map_width - 1u), ymax = float(pc.map_height - 1u);

    // Per particle: affine, centre value and sums. A group's spare slots past the last particle
    // repeat the last one and are not written back.
    float a[PARTICLES_PER_GROUP], b[PARTICLES_PER_GROUP], c[PARTICLES_PER_GROUP], d[PARTICLES_PER_GROUP];
    float tx[PARTICLES_PER_GROUP], ty[PARTICLES_PER_GROUP], shift[PARTICLES_PER_GROUP];
    uint n[PARTICLES_PER_GROUP];
    float sj[PARTICLES_PER_GROUP], sjj[PARTICLES_PER_GROUP], sjt[PARTICLES_PER_GROUP], st[PARTICLES_PER_GROUP],
        stt[PARTICLES_PER_GROUP];
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        uint pid = min(first + p, pc.particle_count - 1u);
        a[p] = affines[6u * pid + 0u], b[p] = affines[6u * pid + 1u];
        c[p] = affines[6u * pid + 2u], d[p] = affines[6u * pid + 3u];
        tx[p] = affines[6u * pid + 4u], ty[p] = affines[6u * pid + 5u];
        shift[p] = map_value(clamp(tx[p], 0.0, xmax), clamp(ty[p], 0.0, ymax));
        n[p] = 0u;
        sj[p] = 0.0, sjj[p] = 0.0, sjt[p] = 0.0, st[p] = 0.0, stt[p] = 0.0;
    }

    // Two-level float sums: short runs of TRN_RUN samples per invocation, then the runs' totals,
    // which keeps rounding error small even when one invocation covers thousands of samples.
    const uint run_span = WORKGROUP_SIZE * TRN_RUN;
    for (uint base = lid; base < SAMPLE_COUNT; base += run_span) {
        float rj[PARTICLES_PER_GROUP], rjj[PARTICLES_PER_GROUP], rjt[PARTICLES_PER_GROUP], rt[PARTICLES_PER_GROUP],
            rtt[PARTICLES_PER_GROUP];
        for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) rj[p] = 0.0, rjj[p] = 0.0, rjt[p] = 0.0, rt[p] = 0.0, rtt[p] = 0.0;
        uint end = min(SAMPLE_COUNT, base + run_span);
        for (uint k = base; k < end; k += WORKGROUP_SIZE) {
            uint pixel = DENSE ? k : table[SAMPLE_COUNT + k];
            float du = float(pixel % TEMPLATE_WIDTH) - pc.cx;
            float dv = float(pixel / TEMPLATE_WIDTH) - pc.cy;
            float t = uintBitsToFloat(table[k]);
            for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
                precise float px = (tx[p] + a[p] * du) + b[p] * dv;
                precise float py = (ty[p] + c[p] * du) + d[p] * dv;
                bool valid = px >= 0.0 && py >= 0.0 && px <= xmax && py <= ymax;
                // Clamped so that invalid samples still read inside the map; a valid position is unchanged.
                float j = map_value(clamp(px, 0.0, xmax), clamp(py, 0.0, ymax)) - shift[p];
                // Invalid samples add zeros (selects rather than multiplies by 0 / 1: measured faster on lavapipe).
                j = valid ? j : 0.0;
                float tv = valid ? t : 0.0;
                n[p] += valid ? 1u : 0u;
                rj[p] += j;
                rjj[p] += j * j;
                rjt[p] += j * t;
                rt[p] += tv;
                rtt[p] += tv * t;
            }
        }
        for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
            sj[p] += rj[p];
            sjj[p] += rjj[p];
            sjt[p] += rjt[p];
            st[p] += rt[p];
            stt[p] += rtt[p];
        }
    }

#ifdef TRN_SUBGROUP_REDUCE
    // Subgroup sums first (the device's subgroup size, never assumed), then invocation p adds
    // particle p's subgroup results in subgroup order.
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        uint sn = subgroupAdd(n[p]);
        float s0 = subgroupAdd(sj[p]), s1 = subgroupAdd(sjj[p]), s2 = subgroupAdd(sjt[p]);
        float s3 = subgroupAdd(st[p]), s4 = subgroupAdd(stt[p]);
        if (subgroupElect()) {
            uint at = p * WORKGROUP_SIZE + gl_SubgroupID;
            red_n[at] = sn;
            red_f[(p * 5u + 0u) * WORKGROUP_SIZE + gl_SubgroupID] = s0;
            red_f[(p * 5u + 1u) * WORKGROUP_SIZE + gl_SubgroupID] = s1;
            red_f[(p * 5u + 2u) * WORKGROUP_SIZE + gl_SubgroupID] = s2;
            red_f[(p * 5u + 3u) * WORKGROUP_SIZE + gl_SubgroupID] = s3;
            red_f[(p * 5u + 4u) * WORKGROUP_SIZE + gl_SubgroupID] = s4;
        }
    }
    barrier();
    const uint partials = gl_NumSubgroups;
#else
    // Shared-memory tree reduction (WORKGROUP_SIZE is a power of two).
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        red_n[p * WORKGROUP_SIZE + lid] = n[p];
        red_f[(p * 5u + 0u) * WORKGROUP_SIZE + lid] = sj[p];
        red_f[(p * 5u + 1u) * WORKGROUP_SIZE + lid] = sjj[p];
        red_f[(p * 5u + 2u) * WORKGROUP_SIZE + lid] = sjt[p];
        red_f[(p * 5u + 3u) * WORKGROUP_SIZE + lid] = st[p];
        red_f[(p * 5u + 4u) * WORKGROUP_SIZE + lid] = stt[p];
    }
    barrier();
    for (uint half_size = WORKGROUP_SIZE / 2u; half_size > 0u; half_size /= 2u) {
        if (lid < half_size) {
            for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
                red_n[p * WORKGROUP_SIZE + lid] += red_n[p * WORKGROUP_SIZE + lid + half_size];
                for (uint f = 0u; f < 5u; ++f)
                    red_f[(p * 5u + f) * WORKGROUP_SIZE + lid] += red_f[(p * 5u + f) * WORKGROUP_SIZE + lid + half_size];
            }
        }
        barrier();
    }
    const uint partials = 1u;
#endif
    // Invocation p writes particle p's sums.
    for (uint p = 0u; p < PARTICLES_PER_GROUP; ++p) {
        if (lid != p % WORKGROUP_SIZE || first + p >= pc.particle_count) continue;
        uint tn = 0u;
        float t0 = 0.0, t1 = 0.0, t2 = 0.0, t3 = 0.0, t4 = 0.0;
        for (uint s = 0u; s < partials; ++s) {
            tn += red_n[p * WORKGROUP_SIZE + s];
            t0 += red_f[(p * 5u + 0u) * WORKGROUP_SIZE + s];
            t1 += red_f[(p * 5u + 1u) * WORKGROUP_SIZE + s];
            t2 += red_f[(p * 5u + 2u) * WORKGROUP_SIZE + s];
            t3 += red_f[(p * 5u + 3u) * WORKGROUP_SIZE + s];
            t4 += red_f[(p * 5u + 4u) * WORKGROUP_SIZE + s];
        }
        uint pid = first + p;
        sums[pid].n = tn;
        sums[pid].sj = t0;
        sums[pid].sjj = t1;
        sums[pid].sjt = t2;
        sums[pid].st = t3;
        sums[pid].stt = t4;
        sums[pid].shift = shift[p];
        sums[pid].unused = 0.0;
    }
}
