// Per-pixel validity -> one bit per bilinear cell (trn/impl/cell_mask.hpp).
#include "trn/impl/cell_mask.hpp"

#include <bit>

namespace trn {

CellMask make_cell_mask(GrayView valid) {
    CellMask m;
    m.cells_x = valid.width - 1;
    m.cells_y = valid.height - 1;
    m.words_per_row = (m.cells_x + 31) / 32;
    m.words.assign(std::size_t(m.words_per_row) * std::size_t(m.cells_y), 0u);
    std::int64_t valid_cells = 0;
    for (int y = 0; y < m.cells_y; ++y) {
        const std::uint8_t *top = valid.row(y), *bottom = valid.row(y + 1);
        std::uint32_t* out = m.words.data() + std::size_t(y) * std::size_t(m.words_per_row);
        bool left = top[0] != 0 && bottom[0] != 0;  // column x of the row pair: both pixels valid
        for (int x = 0; x < m.cells_x; ++x) {
            const bool right = top[x + 1] != 0 && bottom[x + 1] != 0;
            if (left && right) out[x >> 5] |= 1u << (x & 31);
            left = right;
        }
        for (int w = 0; w < m.words_per_row; ++w) valid_cells += std::popcount(out[w]);
    }
    m.invalid_cells = std::int64_t(m.cells_x) * m.cells_y - valid_cells;
    return m;
}

}  // namespace trn
