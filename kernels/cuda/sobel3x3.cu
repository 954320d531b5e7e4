// 3x3 Sobel, u8 in, int16 Gx and Gy out, BORDER_REFLECT_101: bit-exact with
// cv::Sobel(src, CV_16S, 1, 0 / 0, 1, 3). The layout is kernels/opencl/sobel3x3.cl's:
//
// Source rows are `pitch` bytes (a multiple of 64), the image row starting at TRN_SOBEL_PAD, so
// every 16-pixel strip is one aligned 16-byte load. The byte left of each row and the byte right
// of it hold the reflect-101 neighbours (sobel3x3_columns writes them first); rows above and below
// the image are reflected by row index. So the main kernel has no per-pixel border branch.
//
// One thread computes a strip of 16 pixels over `rows_per_item` rows, keeping the horizontal sums
// of the two previous rows (each source row is loaded once per strip). Outputs are packed with a
// pitch of `out_pitch` int16 (a multiple of 16); the host copies the width x height block out.
// Lanes past the width compute values nobody reads.
#include "trn_cuda_args.h"

namespace {

// BORDER_REFLECT_101 index for -1 <= i <= n (-1 -> 1, n -> n-2); an axis of length 1 maps
// everything to 0; indices further out are clamped so that no read leaves the image.
__device__ __forceinline__ int reflect101(int i, int n) {
    if (n == 1) return 0;
    if (i < 0) i = -i;
    if (i >= n) i = 2 * n - 2 - i;
    return min(max(i, 0), n - 1);
}

// Horizontal parts of one source row over a strip: d = p[x+1] - p[x-1], s = p[x-1] + 2 p[x] + p[x+1].
__device__ __forceinline__ void sobel_row(const unsigned char* p, int d[TRN_SOBEL_STRIP], int s[TRN_SOBEL_STRIP]) {
    const uint4 words = *reinterpret_cast<const uint4*>(p);
    const unsigned int w[4] = {words.x, words.y, words.z, words.w};
    int c[TRN_SOBEL_STRIP + 2];
    c[0] = p[-1];
    c[TRN_SOBEL_STRIP + 1] = p[TRN_SOBEL_STRIP];
#pragma unroll
    for (int i = 0; i < TRN_SOBEL_STRIP; ++i) c[i + 1] = (w[i / 4] >> (8 * (i % 4))) & 0xffu;
#pragma unroll
    for (int i = 0; i < TRN_SOBEL_STRIP; ++i) {
        d[i] = c[i + 2] - c[i];
        s[i] = c[i] + 2 * c[i + 1] + c[i + 2];
    }
}

// 16 int16 values as two aligned 16-byte stores.
__device__ __forceinline__ void store_strip(short* out, const int v[TRN_SOBEL_STRIP]) {
    unsigned int packed[TRN_SOBEL_STRIP / 2];
#pragma unroll
    for (int i = 0; i < TRN_SOBEL_STRIP / 2; ++i)
        packed[i] = (static_cast<unsigned int>(v[2 * i]) & 0xffffu) | (static_cast<unsigned int>(v[2 * i + 1]) << 16);
    uint4* o = reinterpret_cast<uint4*>(out);
    o[0] = make_uint4(packed[0], packed[1], packed[2], packed[3]);
    o[1] = make_uint4(packed[4], packed[5], packed[6], packed[7]);
}

}  // namespace

// Border pass: thread 2y writes the left neighbour of row y, thread 2y+1 the right one.
extern "C" __global__ void sobel3x3_columns(const TrnSobelArgs args) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= 2 * args.height) return;
    unsigned char* row = reinterpret_cast<unsigned char*>(args.src) + static_cast<size_t>(i >> 1) * args.pitch + TRN_SOBEL_PAD;
    const int x = (i & 1) ? args.width : -1;
    row[x] = row[reflect101(x, args.width)];
}

// Grid: strips x row blocks, rounded up to whole blocks; threads past the image return.
extern "C" __global__ void sobel3x3(const TrnSobelArgs args) {
    const int x = (blockIdx.x * blockDim.x + threadIdx.x) * TRN_SOBEL_STRIP;
    const int y0 = (blockIdx.y * blockDim.y + threadIdx.y) * args.rows_per_item;
    if (x >= args.width || y0 >= args.height) return;
    const int y1 = min(y0 + args.rows_per_item, args.height);
    const unsigned char* strip = reinterpret_cast<const unsigned char*>(args.src) + TRN_SOBEL_PAD + x;
    short* gx = reinterpret_cast<short*>(args.gx);
    short* gy = reinterpret_cast<short*>(args.gy);
    int d0[TRN_SOBEL_STRIP], s0[TRN_SOBEL_STRIP], d1[TRN_SOBEL_STRIP], s1[TRN_SOBEL_STRIP], d2[TRN_SOBEL_STRIP],
        s2[TRN_SOBEL_STRIP], out[TRN_SOBEL_STRIP];
    sobel_row(strip + static_cast<size_t>(reflect101(y0 - 1, args.height)) * args.pitch, d0, s0);
    sobel_row(strip + static_cast<size_t>(y0) * args.pitch, d1, s1);
    for (int y = y0; y < y1; ++y) {
        sobel_row(strip + static_cast<size_t>(reflect101(y + 1, args.height)) * args.pitch, d2, s2);
        const size_t at = static_cast<size_t>(y) * args.out_pitch + x;
#pragma unroll
        for (int i = 0; i < TRN_SOBEL_STRIP; ++i) out[i] = d0[i] + 2 * d1[i] + d2[i];
        store_strip(gx + at, out);
#pragma unroll
        for (int i = 0; i < TRN_SOBEL_STRIP; ++i) out[i] = s2[i] - s0[i];
        store_strip(gy + at, out);
#pragma unroll
        for (int i = 0; i < TRN_SOBEL_STRIP; ++i) d0[i] = d1[i], s0[i] = s1[i], d1[i] = d2[i], s1[i] = s2[i];
    }
}
