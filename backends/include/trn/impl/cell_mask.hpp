#pragma once
// For backend implementers only: a map's no-data as the backends see it. Backend::upload_map turns
// the caller's per-pixel validity into one bit per bilinear cell (the 2x2 pixels whose top-left is
// (x, y), x <= W-2, y <= H-2): set when all four pixels are valid. A sample is left out exactly when
// the cell its position selects (scoring.hpp: x0 = min(floor(px), W-2), likewise y0) is not set, so
// every backend needs one bit test per sample, and the mask costs 1/8 byte per map pixel on a device
// (docs/ARCHITECTURE.md, "No-data").
#include <cstddef>
#include <cstdint>
#include <vector>

#include "trn/export.hpp"
#include "trn/image.hpp"

TRN_API_BEGIN
namespace trn {

struct CellMask {
    int cells_x = 0, cells_y = 0;  // the map's width - 1 and height - 1
    int words_per_row = 0;         // ceil(cells_x / 32)
    // Row y of cells is words [y * words_per_row, (y + 1) * words_per_row); cell x is bit x % 32 of
    // word x / 32 (least significant first). Bits past cells_x are 0.
    std::vector<std::uint32_t> words;
    std::int64_t invalid_cells = 0;

    bool valid(int x, int y) const {
        return (words[std::size_t(y) * std::size_t(words_per_row) + std::size_t(x >> 5)] >> (x & 31)) & 1u;
    }
    // Bytes of `words` for a width x height map: the one size the backends allocate and quote.
    static double bytes(std::int64_t width, std::int64_t height) {
        return 4.0 * double((width - 1 + 31) / 32) * double(height - 1);
    }
};

// The cell mask of a map whose pixel (x, y) is valid where valid.at(x, y) != 0 (the map's size, >= 2x2).
CellMask make_cell_mask(GrayView valid);

}  // namespace trn
TRN_API_END
