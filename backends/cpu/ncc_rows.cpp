// Portable inner loops; branch-free so the compiler can vectorize what it can.
#include "ncc_rows.hpp"

#include <algorithm>

namespace trn::cpu {
namespace {

template <bool Checked>
RowSums sample_row(const MapPixels& m, const RowInput& row, float shift) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    const int x0max = m.width - 2, y0max = m.height - 2;
    RowSums r;
    for (int k = 0; k < row.count; ++k) {
        float px = row.ax[k] + (row.bdvs ? row.bdvs[k] : row.bdv);
        float py = row.ay[k] + (row.ddvs ? row.ddvs[k] : row.ddv);
        float valid = 1.0f;
        if constexpr (Checked) {
            valid = (px >= 0.0f && py >= 0.0f && px <= xmax && py <= ymax) ? 1.0f : 0.0f;
            px = std::clamp(px, 0.0f, xmax);  // keeps the loads in bounds; masked out below
            py = std::clamp(py, 0.0f, ymax);
        }
        const int x0 = std::min(int(px), x0max), y0 = std::min(int(py), y0max);  // px >= 0: int() == floor
        const float fx = px - float(x0), fy = py - float(y0);
        const std::uint8_t* p = m.data + std::ptrdiff_t(y0) * m.stride + x0;
        const float m00 = p[0], m10 = p[1], m01 = p[m.stride], m11 = p[m.stride + 1];
        const float top = m00 + fx * (m10 - m00), bot = m01 + fx * (m11 - m01);
        const float j = (top + fy * (bot - top)) - shift;
        const float t = row.t[k];
        r.n += valid;
        r.sj += valid * j;
        r.sjj += valid * j * j;
        r.sjt += valid * j * t;
        r.st += valid * t;
        r.stt += valid * t * t;
    }
    return r;
}

}  // namespace

RowSums sample_row_checked(const MapPixels& m, const RowInput& row, float shift) { return sample_row<true>(m, row, shift); }
RowSums sample_row_inside(const MapPixels& m, const RowInput& row, float shift) { return sample_row<false>(m, row, shift); }

bool avx2_available() {
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

}  // namespace trn::cpu
