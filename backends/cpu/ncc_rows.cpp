// Portable inner loops; branch-free so the compiler can vectorize what it can.
#include "ncc_rows.hpp"

#include <algorithm>

#include "trn/fixed_point.hpp"

namespace trn::cpu {
namespace {

// A sample counts when its rounded position is on the map (both samplers that check use this).
bool on_map(float px, float py, float xmax, float ymax) { return px >= 0.0f && py >= 0.0f && px <= xmax && py <= ymax; }

template <bool Checked>
RowSums sample_row(const MapPixels& m, const RowInput& row) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    const int x0max = m.width - 2, y0max = m.height - 2;
    RowSums r;
    for (int k = 0; k < row.count; ++k) {
        float px = row.ax[k] + (row.bdvs ? row.bdvs[k] : row.bdv);
        float py = row.ay[k] + (row.ddvs ? row.ddvs[k] : row.ddv);
        std::int64_t valid = 1;
        if constexpr (Checked) {
            valid = on_map(px, py, xmax, ymax) ? 1 : 0;
            px = std::clamp(px, 0.0f, xmax);  // keeps the loads in bounds; masked out below
            py = std::clamp(py, 0.0f, ymax);
        }
        const int x0 = std::min(int(px), x0max), y0 = std::min(int(py), y0max);  // px >= 0: int() == floor
        if constexpr (Checked)
            if (m.cell_mask)  // a cell holding no-data leaves the sample out
                valid &= (m.cell_mask[std::ptrdiff_t(y0) * m.mask_words_per_row + (x0 >> 5)] >> (x0 & 31)) & 1u;
        const float fx = px - float(x0), fy = py - float(y0);
        const std::uint8_t* p = m.pairs + std::ptrdiff_t(y0) * m.pair_stride + 2 * std::ptrdiff_t(x0);  // m00 m01 m10 m11
        const std::int64_t j = valid * fixed::bilinear(p[0], p[2], p[1], p[3], fixed::weight(fx), fixed::weight(fy));
        const std::int64_t t = row.t[k];
        r.sj += j;
        r.sjj += j * j;
        r.sjt += j * t;
        if constexpr (Checked) {
            r.n += valid;
            r.st += valid * t;
            r.stt += valid * t * t;
        }
    }
    return r;
}

}  // namespace

RowSums sample_row_checked(const MapPixels& m, const RowInput& row) { return sample_row<true>(m, row); }
RowSums sample_row_inside(const MapPixels& m, const RowInput& row) { return sample_row<false>(m, row); }

RowSums sample_row_clipped(const MapPixels& m, const RowInput& row, bool vector) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    auto inside = [&](int k) { return on_map(row.ax[k] + row.bdv, row.ay[k] + row.ddv, xmax, ymax); };  // the same rounded position
    int first = 0, end = row.count;
    while (first < end && !inside(first)) ++first;
    while (end > first && !inside(end - 1)) --end;
    RowInput run = row;
    run.ax += first, run.ay += first, run.t += first, run.count = end - first;
    RowSums r;
    if (run.count == 0) return r;
    r = vector ? sample_row_inside_avx2(m, run) : sample_row_inside(m, run);
    r.n = run.count;
    for (int k = 0; k < run.count; ++k) r.st += run.t[k], r.stt += std::int64_t(run.t[k]) * run.t[k];
    return r;
}

bool avx2_available() {
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

}  // namespace trn::cpu
