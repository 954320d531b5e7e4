#version 450
// 3x3 Sobel (cv::Sobel CV_16S, ksize 3, BORDER_REFLECT_101) of one band of rows.
//
// Source layout (the host writes it): band rows 0 .. rows+1 are image rows y0-1 .. y0+rows, the
// first and last reflected on the host; each row is src_pitch 16-byte blocks, the image row
// starting at block 1. Byte 15 (left of the row) and byte 16 + width (right of it) hold the
// reflect-101 column neighbours, also written by the host. So no invocation needs a border
// branch: each reads the aligned block of its strip plus the block before and after it (one
// 16-byte load each; on lavapipe a per-invocation load costs the same for 4 bytes or 16).
//
// Work: one invocation computes a strip of 16 pixels (4 source words) over up to rows_per_item
// rows, keeping the previous rows' values so each source row is loaded once per strip. Outputs
// are int16 pairs in 32-bit words (no 16-bit storage needed), stored as two 16-byte blocks per
// strip, out_pitch blocks per row; lanes past the width compute values the host ignores.
#extension GL_EXT_control_flow_attributes : require

layout(constant_id = 0) const uint GROUP_X = 8;
layout(constant_id = 1) const uint GROUP_Y = 32;
layout(local_size_x_id = 0, local_size_y_id = 1) in;

layout(std430, binding = 0) readonly buffer Source { uvec4 src[]; };
layout(std430, binding = 1) writeonly buffer GradX { uvec4 gx[]; };
layout(std430, binding = 2) writeonly buffer GradY { uvec4 gy[]; };

layout(push_constant) uniform Push {
    uint width;
    uint rows;           // output rows in this band
    uint src_pitch;      // 16-byte blocks per source row (strips + 2)
    uint out_pitch;      // 16-byte blocks per output row (2 * strips)
    uint rows_per_item;  // output rows per invocation
} pc;

const int N = 16;  // pixels per strip

// Pixels x0-1 .. x0+16 of band row `row` (v[i] is pixel x0 - 1 + i).
void load_row(uint row, uint strip, out int v[N + 2]) {
    uint at = row * pc.src_pitch + strip;  // the block before the strip
    v[0] = int(src[at].w >> 24u);
    uvec4 c = src[at + 1u];
    [[unroll]] for (int k = 0; k < 4; ++k) {
        uint w = c[k];
        v[4 * k + 1] = int(w & 0xFFu);
        v[4 * k + 2] = int((w >> 8u) & 0xFFu);
        v[4 * k + 3] = int((w >> 16u) & 0xFFu);
        v[4 * k + 4] = int(w >> 24u);
    }
    v[N + 1] = int(src[at + 2u].x & 0xFFu);
}

uint pack(int lo, int hi) { return (uint(lo) & 0xFFFFu) | (uint(hi) << 16u); }

void main() {
    uint strip = gl_GlobalInvocationID.x;
    uint y0 = gl_GlobalInvocationID.y * pc.rows_per_item;
    if (2u * strip >= pc.out_pitch || y0 >= pc.rows) return;
    uint y1 = min(y0 + pc.rows_per_item, pc.rows);

    // Band row r is output row r - 1. t, m: raw pixels of the rows above and at the output row;
    // ht, hm: their horizontal smoothing p[x-1] + 2 p[x] + p[x+1].
    int t[N + 2], m[N + 2], b[N + 2];
    int ht[N], hm[N];
    load_row(y0, strip, t);
    load_row(y0 + 1u, strip, m);
    [[unroll]] for (int i = 0; i < N; ++i) {
        ht[i] = t[i] + 2 * t[i + 1] + t[i + 2];
        hm[i] = m[i] + 2 * m[i + 1] + m[i + 2];
    }
    for (uint y = y0; y < y1; ++y) {
        load_row(y + 2u, strip, b);
        int v[N + 2];  // vertical smoothing of the three rows
        [[unroll]] for (int i = 0; i < N + 2; ++i) v[i] = t[i] + 2 * m[i] + b[i];
        int hb[N];
        [[unroll]] for (int i = 0; i < N; ++i) hb[i] = b[i] + 2 * b[i + 1] + b[i + 2];
        uint ox[N / 2], oy[N / 2];
        [[unroll]] for (int k = 0; k < N / 2; ++k) {
            ox[k] = pack(v[2 * k + 2] - v[2 * k], v[2 * k + 3] - v[2 * k + 1]);
            oy[k] = pack(hb[2 * k] - ht[2 * k], hb[2 * k + 1] - ht[2 * k + 1]);
        }
        uint o = y * pc.out_pitch + 2u * strip;
        gx[o] = uvec4(ox[0], ox[1], ox[2], ox[3]);
        gx[o + 1u] = uvec4(ox[4], ox[5], ox[6], ox[7]);
        gy[o] = uvec4(oy[0], oy[1], oy[2], oy[3]);
        gy[o + 1u] = uvec4(oy[4], oy[5], oy[6], oy[7]);
        t = m;
        m = b;
        ht = hm;
        hm = hb;
    }
}
