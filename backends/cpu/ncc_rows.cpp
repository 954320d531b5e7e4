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

RowSums sample_row_clipped(const MapPixels& m, const RowInput& row, bool vector, const TemplatePrefix& prefix, std::size_t first_sample) {
    const float xmax = float(m.width - 1), ymax = float(m.height - 1);
    auto inside = [&](int k) { return on_map(row.ax[k] + row.bdv, row.ay[k] + row.ddv, xmax, ymax); };  // the same rounded position
    int first = 0, end = row.count;
    while (first < end && !inside(first)) ++first;
    while (end > first && !inside(end - 1)) --end;
    RowSums r;
    if (first == end) return r;
    // Samples [k0, k1) of the row, all on the map, of one kind.
    auto sample = [&](int k0, int k1, CellBlocks::Kind kind) {
        if (kind == CellBlocks::kNoneValid || k0 == k1) return;
        RowInput part = row;
        part.ax += k0, part.ay += k0, part.t += k0, part.count = k1 - k0;
        RowSums s;
        if (kind == CellBlocks::kSome) {
            s = vector ? sample_row_on_map_avx2(m, part) : sample_row_checked(m, part);
        } else {
            s = vector ? sample_row_inside_avx2(m, part) : sample_row_inside(m, part);
            const std::size_t p0 = first_sample + std::size_t(k0), p1 = first_sample + std::size_t(k1);
            s.n = part.count;
            s.st = prefix.st[p1] - prefix.st[p0];
            s.stt = prefix.stt[p1] - prefix.stt[p0];
        }
        r.n += s.n, r.sj += s.sj, r.sjj += s.sjj, r.sjt += s.sjt, r.st += s.st, r.stt += s.stt;
    };
    if (!m.cell_bits) {
        sample(first, end, CellBlocks::kAllValid);
        return r;
    }
    // The cell of sample k (on the map), as the samplers select it.
    const int x0max = m.width - 2, y0max = m.height - 2;
    auto cell_x = [&](int k) { return std::min(int(row.ax[k] + row.bdv), x0max); };
    auto cell_y = [&](int k) { return std::min(int(row.ay[k] + row.ddv), y0max); };
    // The row's run judged whole, then (some valid, some not) in pieces of kPiece; the pieces go
    // out in order, neighbours of one kind joined.
    auto judge = [&](int k0, int k1) {
        const int xa = cell_x(k0), xb = cell_x(k1 - 1), ya = cell_y(k0), yb = cell_y(k1 - 1);
        return m.blocks->judge(std::min(xa, xb), std::min(ya, yb), std::max(xa, xb), std::max(ya, yb));
    };
    const CellBlocks::Kind whole = judge(first, end);
    if (whole != CellBlocks::kSome) {
        sample(first, end, whole);
        return r;
    }
    int start = first;
    CellBlocks::Kind kind = CellBlocks::kAllValid;
    for (int k = first; k < end; k += kPiece) {
        const CellBlocks::Kind piece = judge(k, std::min(k + kPiece, end));
        if (piece != kind) {
            sample(start, k, kind);
            start = k, kind = piece;
        }
    }
    sample(start, end, kind);
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
