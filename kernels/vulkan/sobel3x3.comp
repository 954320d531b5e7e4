#version 450
// 3x3 Sobel (cv::Sobel CV_16S, ksize 3, BORDER_REFLECT_101) of one band of rows.
//
// The host uploads the band's rows with one reflected row above and below (rows -1 and h map by
// reflect-101 on the host), so this shader only reflects columns. Each invocation writes two
// horizontally adjacent pixels as one 32-bit word of two int16 values (no 16-bit storage needed).
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
    uint out_pitch;  // words per output row = ceil(width / 2)
} pc;

// reflect-101: -1 -> 1, width -> width-2; a single column maps every index to 0.
uint reflect_column(int x) {
    int w = int(pc.width);
    if (w == 1) return 0u;
    if (x < 0) return uint(-x);
    if (x >= w) return uint(2 * w - 2 - x);
    return uint(x);
}

int pixel(uint row, uint x) { return int(TRN_BYTE_OF(src, row * pc.src_pitch + x)); }

// Gx and Gy at column x of output row y (source rows y, y+1, y+2 of the band).
ivec2 sobel_at(uint y, int x) {
    uint xl = reflect_column(x - 1), xc = uint(x), xr = reflect_column(x + 1);
    int a0 = pixel(y, xl), a1 = pixel(y, xc), a2 = pixel(y, xr);
    int b0 = pixel(y + 1u, xl), b2 = pixel(y + 1u, xr);
    int c0 = pixel(y + 2u, xl), c1 = pixel(y + 2u, xc), c2 = pixel(y + 2u, xr);
    int gxv = (a2 - a0) + 2 * (b2 - b0) + (c2 - c0);
    int gyv = (c0 + 2 * c1 + c2) - (a0 + 2 * a1 + a2);
    return ivec2(gxv, gyv);
}

void main() {
    uint word = gl_GlobalInvocationID.x;
    uint y = gl_GlobalInvocationID.y;
    if (word >= pc.out_pitch || y >= pc.rows) return;
    int x = int(2u * word);
    ivec2 g0 = sobel_at(y, x);
    ivec2 g1 = x + 1 < int(pc.width) ? sobel_at(y, x + 1) : ivec2(0);
    uint o = y * pc.out_pitch + word;
    gx[o] = (uint(g0.x) & 0xFFFFu) | (uint(g1.x) << 16u);
    gy[o] = (uint(g0.y) & 0xFFFFu) | (uint(g1.y) << 16u);
}
