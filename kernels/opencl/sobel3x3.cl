// 3x3 Sobel, u8 in, int16 Gx and Gy out, BORDER_REFLECT_101: bit-exact with
// cv::Sobel(src, CV_16S, 1, 0 / 0, 1, 3).
//
// Source layout (the host writes it): rows of `pitch` bytes (a multiple of 16), the image row
// starting at byte TRN_SOBEL_PAD so that every 16-pixel strip is an aligned uchar16. The byte
// left of each row (TRN_SOBEL_PAD - 1) and the byte right of it (TRN_SOBEL_PAD + width) hold the
// reflect-101 neighbours, written by sobel3x3_columns; rows above and below the image are
// reflected by row index (once per row, not per pixel). So the main kernel has no per-pixel
// border branch: it reads one aligned vector and two neighbour bytes per row.
//
// Work: one work item computes a strip of 16 pixels over `rows_per_item` rows, keeping the
// horizontal sums of the two previous rows (each source row is loaded once per strip).
// Outputs are packed with a pitch of `out_pitch` int16 (a multiple of 16); the host copies the
// width x height block out. Lanes past the width compute values nobody reads.
#include "trn_common.clh"

#define TRN_SOBEL_PAD 16

// Border pass: item 2y writes the left neighbour of row y, item 2y+1 the right one.
__kernel void sobel3x3_columns(__global uchar* src, int width, int height, int pitch) {
    const int i = (int)get_global_id(0);
    if (i >= 2 * height) return;
    __global uchar* row = src + (size_t)(i >> 1) * (size_t)pitch + TRN_SOBEL_PAD;
    const int x = (i & 1) ? width : -1;
    row[x] = row[trn_reflect101(x, width)];
}

// Horizontal parts of one source row over a strip: d = p[x+1] - p[x-1], s = p[x-1] + 2 p[x] + p[x+1].
void trn_sobel_row(__global const uchar* p, short16* d, short16* s) {
    const uchar16 c = vload16(0, p);
    const uchar16 l = (uchar16)(p[-1], c.s012, c.s3456, c.s789abcde);
    const uchar16 r = (uchar16)(c.s123, c.s4567, c.s89abcdef, p[16]);
    const short16 cs = convert_short16(c), ls = convert_short16(l), rs = convert_short16(r);
    *d = rs - ls;
    *s = ls + (cs + cs) + rs;
}

// Global size: (strips rounded up to the work-group, row blocks rounded up); items past the image return.
__kernel void sobel3x3(__global const uchar* src, int width, int height, int pitch, int rows_per_item,
                       __global short* gx, __global short* gy, int out_pitch) {
    const int x = (int)get_global_id(0) * 16;
    const int y0 = (int)get_global_id(1) * rows_per_item;
    if (x >= width || y0 >= height) return;
    const int y1 = min(y0 + rows_per_item, height);
    __global const uchar* strip = src + TRN_SOBEL_PAD + x;
    short16 d0, s0, d1, s1, d2, s2;
    trn_sobel_row(strip + (size_t)trn_reflect101(y0 - 1, height) * (size_t)pitch, &d0, &s0);
    trn_sobel_row(strip + (size_t)y0 * (size_t)pitch, &d1, &s1);
    for (int y = y0; y < y1; ++y) {
        trn_sobel_row(strip + (size_t)trn_reflect101(y + 1, height) * (size_t)pitch, &d2, &s2);
        const size_t at = (size_t)y * (size_t)out_pitch + (size_t)x;
        vstore16(d0 + (d1 + d1) + d2, 0, gx + at);
        vstore16(s2 - s0, 0, gy + at);
        d0 = d1, s0 = s1, d1 = d2, s1 = s2;
    }
}
