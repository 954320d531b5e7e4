// 3x3 Sobel, u8 in, int16 Gx and Gy out, BORDER_REFLECT_101: bit-exact with
// cv::Sobel(src, CV_16S, 1, 0 / 0, 1, 3). Each work-group loads its tile plus a one-pixel
// apron into local memory once, so every source pixel is read from global memory ~once.
// Source and outputs are packed (row stride = width); the host copies ROIs in and out.
#include "trn_common.clh"

#ifndef TRN_TILE
#define TRN_TILE 16  // the work-group is TRN_TILE x TRN_TILE (the build passes -D)
#endif
#define TRN_APRON (TRN_TILE + 2)

__kernel __attribute__((reqd_work_group_size(TRN_TILE, TRN_TILE, 1)))
void sobel3x3(__global const uchar* src, int width, int height, __global short* gx, __global short* gy) {
    __local short tile[TRN_APRON][TRN_APRON];
    const int lx = (int)get_local_id(0);
    const int ly = (int)get_local_id(1);
    const int left = (int)get_group_id(0) * TRN_TILE - 1;
    const int top = (int)get_group_id(1) * TRN_TILE - 1;
    for (int i = ly * TRN_TILE + lx; i < TRN_APRON * TRN_APRON; i += TRN_TILE * TRN_TILE) {
        const int tx = i % TRN_APRON;
        const int ty = i / TRN_APRON;
        const int sx = trn_reflect101(left + tx, width);
        const int sy = trn_reflect101(top + ty, height);
        tile[ty][tx] = (short)src[(size_t)sy * (size_t)width + (size_t)sx];
    }
    barrier(CLK_LOCAL_MEM_FENCE);

    const int x = (int)get_global_id(0);
    const int y = (int)get_global_id(1);
    if (x >= width || y >= height) return;
    const int cx = lx + 1, cy = ly + 1;
    const int a0 = tile[cy - 1][cx - 1], a1 = tile[cy - 1][cx], a2 = tile[cy - 1][cx + 1];
    const int b0 = tile[cy][cx - 1], b2 = tile[cy][cx + 1];
    const int c0 = tile[cy + 1][cx - 1], c1 = tile[cy + 1][cx], c2 = tile[cy + 1][cx + 1];
    const size_t at = (size_t)y * (size_t)width + (size_t)x;
    gx[at] = (short)((a2 - a0) + 2 * (b2 - b0) + (c2 - c0));
    gy[at] = (short)((c0 + 2 * c1 + c2) - (a0 + 2 * a1 + a2));
}
