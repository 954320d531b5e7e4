#pragma once
// Power-of-two rounding for work-group sizes: every device backend keeps its groups powers of two
// (tree reductions halve them), within the device's limits.
#include <concepts>

namespace trn {

// Largest power of two <= v (1 for v <= 1).
template <std::unsigned_integral T>
constexpr T floor_pow2(T v) {
    T p = 1;
    while (p <= v / 2) p *= 2;
    return p;
}

}  // namespace trn
