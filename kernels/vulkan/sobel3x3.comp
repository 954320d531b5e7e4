#version 450
// 3x3 Sobel (cv::Sobel CV_16S, ksize 3, BORDER_REFLECT_101) of one band of rows.
//
// The host uploads the band's rows with one reflected row above and below (rows -1 and h map by
// reflect-101 on the host), so this shader only reflects columns. Each invocation writes four
// horizontally adjacent pixels as two 32-bit words of int16 pairs (no 16-bit storage needed);
// away from the left/right borders it reads the 6 source columns it needs as 3 aligned words per row.
#extension GL_GOOGLE_include_directive : require
#include "map_access.glsl"

layout(constant_id = 0) const uint GROUP_X = 64;
layout(constant_id = 1) const uint GROUP_Y = 1;
layout(local_size_x_id = 0, local_size_y_id = 1) in;

layout(std430, binding = 0) readonly buffer Source { uint src[]; };  // (rows + 2) rows of src_pitch bytes
layout(std430, binding = 1) writeonly buffer GradX { uint gx[]; };    // rows rows of out_pitch words
layout(std430, binding = 2) writeonly buffer GradY { uint gy[]; };

layout(push_constant) uniform Push {
    uint width;
    uint rows;       // output rows in this band
    uint src_pitch;  // bytes per uploaded source row (multiple of 4)
    uint out_pitch;  // words per output row = 2 * ceil(width / 4)
} pc;

// reflect-101: -1 -> 1, width -> width-2; a single column maps every index to 0. Columns past the
// image (only in the last, partial quad, whose extra outputs the host ignores) are clamped.
uint reflect_column(int x) {
    int w = int(pc.width);
    if (w == 1) return 0u;
    if (x < 0) x = -x;
    if (x >= w) x = 2 * w - 2 - x;
    return uint(clamp(x, 0, w - 1));
}

// Source columns x0-1 .. x0+4 of band row `row`.
void load_columns(uint row, int x0, bool interior, out int p[6]) {
    uint base = row * pc.src_pitch;
    if (interior) {
        uint w = (base + uint(x0)) >> 2u;
        uint left = src[w - 1u], mid = src[w], right = src[w + 1u];
        p[0] = int(left >> 24u);
        p[1] = int(mid & 0xFFu);
        p[2] = int((mid >> 8u) & 0xFFu);
        p[3] = int((mid >> 16u) & 0xFFu);
        p[4] = int(mid >> 24u);
        p[5] = int(right & 0xFFu);
    } else {
        for (int i = 0; i < 6; ++i) p[i] = int(TRN_BYTE_OF(src, base + reflect_column(x0 - 1 + i)));
    }
}

uint pack(int lo, int hi) { return (uint(lo) & 0xFFFFu) | (uint(hi) << 16u); }

void main() {
    uint quad = gl_GlobalInvocationID.x;
    uint y = gl_GlobalInvocationID.y;
    if (2u * quad >= pc.out_pitch || y >= pc.rows) return;
    int x0 = int(4u * quad);
    bool interior = x0 >= 1 && x0 + 4 <= int(pc.width) - 1;
    int a[6], b[6], c[6];
    load_columns(y, x0, interior, a);
    load_columns(y + 1u, x0, interior, b);
    load_columns(y + 2u, x0, interior, c);
    int ox[4], oy[4];
    for (int i = 0; i < 4; ++i) {
        ox[i] = (a[i + 2] - a[i]) + 2 * (b[i + 2] - b[i]) + (c[i + 2] - c[i]);
        oy[i] = (c[i] + 2 * c[i + 1] + c[i + 2]) - (a[i] + 2 * a[i + 1] + a[i + 2]);
    }
    uint o = y * pc.out_pitch + 2u * quad;
    gx[o] = pack(ox[0], ox[1]);
    gx[o + 1u] = pack(ox[2], ox[3]);
    gy[o] = pack(oy[0], oy[1]);
    gy[o + 1u] = pack(oy[2], oy[3]);
}
