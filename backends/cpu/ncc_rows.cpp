// Portable inner loops; branch-free so the compiler can vectorize what it can.
#include "ncc_rows.hpp"

#include <algorithm>

#include "row_kernels.hpp"
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
            // Keeps the loads in bounds (the sample is masked out above). Not std::clamp: it returns
            // a NaN position as NaN, and int(NaN) is undefined (INT_MIN on x86: a load far outside).
            px = px >= 0.0f ? std::min(px, xmax) : 0.0f;
            py = py >= 0.0f ? std::min(py, ymax) : 0.0f;
        }
        const int x0 = std::min(int(px), x0max), y0 = std::min(int(py), y0max);  // px >= 0: int() == floor
        if constexpr (Checked)
            if (m.cell_bits) {  // a cell holding no-data leaves the sample out
                const std::ptrdiff_t bit = std::ptrdiff_t(y0) * (m.width - 1) + x0;
                valid &= (m.cell_bits[bit >> 5] >> (bit & 31)) & 1u;
            }
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

RowSums sample_row_clipped(const MapPixels& m, const RowInput& row, const RowKernels& kernels, const TemplatePrefix& prefix,
                           std::size_t first_sample) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    auto inside = [&](int k) { return on_map(row.ax[k] + row.bdv, row.ay[k] + row.ddv, xmax, ymax); };  // the same rounded position
    int first = 0, end = row.count;
    while (first < end && !inside(first)) ++first;
    while (end > first && !inside(end - 1)) --end;
    RowInput run = row;
    run.ax += first, run.ay += first, run.t += first, run.count = end - first;
    RowSums r;
    if (run.count == 0) return r;
    r = kernels.inside(m, run);
    const std::size_t k0 = first_sample + std::size_t(first), k1 = first_sample + std::size_t(end);
    r.n = run.count;
    r.st = prefix.st[k1] - prefix.st[k0];
    r.stt = prefix.stt[k1] - prefix.stt[k0];
    return r;
}

Tile judge_tile(const MapPixels& m, const float (&px)[4], const float (&py)[4]) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    bool all_on = true, left = true, above = true, right = true, below = true;  // every corner on the map; off one side
    int x_lo = m.width, y_lo = m.height, x_hi = -1, y_hi = -1;
    for (int i = 0; i < 4; ++i) {
        if (px[i] != px[i] || py[i] != py[i]) return Tile::kSome;  // NaN: nothing is known
        all_on = all_on && on_map(px[i], py[i], xmax, ymax);
        left = left && px[i] < 0.0f, above = above && py[i] < 0.0f, right = right && px[i] > xmax, below = below && py[i] > ymax;
        // The cell as sample_row_checked selects it: position clamped to the map.
        const int x0 = std::min(int(std::clamp(px[i], 0.0f, xmax)), m.width - 2);
        const int y0 = std::min(int(std::clamp(py[i], 0.0f, ymax)), m.height - 2);
        x_lo = std::min(x_lo, x0), y_lo = std::min(y_lo, y0), x_hi = std::max(x_hi, x0), y_hi = std::max(y_hi, y0);
    }
    if (left || above || right || below) return Tile::kNoneValid;  // the whole tile off one side of the map
    const CellBlocks::Kind cells = m.blocks ? m.blocks->judge(x_lo, y_lo, x_hi, y_hi) : CellBlocks::kAllValid;
    if (cells == CellBlocks::kNoneValid) return Tile::kNoneValid;
    if (!all_on) return Tile::kSome;
    return cells == CellBlocks::kAllValid ? Tile::kAllValid : Tile::kSomeOnMap;
}

RowSums sample_row_tiles(const MapPixels& m, const RowInput& row, const RowKernels& kernels, const TemplatePrefix& prefix,
                         std::size_t first_sample, const Tile* tiles) {
    if (kernels.tiles) return kernels.tiles(m, row, prefix, first_sample, tiles);
    RowSums r;
    const int count = (row.count + kTileCols - 1) / kTileCols;
    for (int i = 0; i < count;) {
        int j = i + 1;
        while (j < count && tiles[j] == tiles[i]) ++j;
        const int k0 = i * kTileCols, k1 = std::min(j * kTileCols, row.count);
        const Tile kind = tiles[i];
        i = j;
        if (kind == Tile::kNoneValid) continue;
        RowInput part = row;
        part.ax += k0, part.ay += k0, part.t += k0, part.count = k1 - k0;
        RowSums s;
        if (kind == Tile::kAllValid) {
            s = kernels.inside(m, part);
            const std::size_t p0 = first_sample + std::size_t(k0), p1 = first_sample + std::size_t(k1);
            s.n = part.count;
            s.st = prefix.st[p1] - prefix.st[p0];
            s.stt = prefix.stt[p1] - prefix.stt[p0];
        } else {
            s = kernels.checked(m, part);
        }
        r.n += s.n, r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt, r.st += s.st, r.stt += s.stt;
    }
    return r;
}

}  // namespace trn::cpu
