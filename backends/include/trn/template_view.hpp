#pragma once
// A camera template as the caller has it: 8-bit grey or float, with a row stride.
#include <cstdint>

#include "trn/image.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct TemplateView {
    enum class Type { U8, F32 };
    const void* data = nullptr;
    Type type = Type::U8;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;  // elements between row starts

    TemplateView() = default;
    TemplateView(GrayView v) : data(v.data), type(Type::U8), width(v.width), height(v.height), stride(v.stride) {}
    TemplateView(FloatView v) : data(v.data), type(Type::F32), width(v.width), height(v.height), stride(v.stride) {}

    double at(int x, int y) const {
        return type == Type::U8 ? static_cast<const std::uint8_t*>(data)[y * stride + x]
                                : static_cast<const float*>(data)[y * stride + x];
    }
};

}  // namespace trn
TRN_API_END
