#pragma once
// Non-owning views of 2-D pixel buffers with an explicit row stride (in elements), so that ROIs
// of larger images can be passed without copying.
#include <cstddef>
#include <cstdint>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

template <typename T>
struct ImageView {
    T* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;  // elements between the starts of two rows (>= width)

    T* row(int y) const { return data + y * stride; }
    T& at(int x, int y) const { return data[y * stride + x]; }
    bool empty() const { return data == nullptr || width <= 0 || height <= 0; }
    // A sub-rectangle sharing this view's memory.
    ImageView roi(int x, int y, int w, int h) const { return {data + y * stride + x, w, h, stride}; }
};

using GrayView = ImageView<const std::uint8_t>;
using Int16View = ImageView<std::int16_t>;
using FloatView = ImageView<const float>;

}  // namespace trn
TRN_API_END
