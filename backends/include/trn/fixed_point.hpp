#pragma once
// The integer definition of a scoring sample (scoring.hpp), shared by the C++ backends; the OpenCL
// and Vulkan kernels spell out the same operations.
//
// Why 7-bit weights: a pixel times a weight (<= 255 * 128 = 32640) and the weight pairs
// (128 - w, w) fit signed 16-bit lanes, so the interpolation can run as int16 multiply-adds
// (_mm256_madd_epi16, GPU 16-bit math) and the value I fits int16 as well. 1/128 px is 4x finer
// than OpenCV's warpAffine (5 bits, 1/32 px) and the resolution a float position still has at the
// largest map side (limits.hpp); GPU texture units use 8 bits, which would not fit int16 lanes.
// Measured effect on scores: docs/ARCHITECTURE.md ("Exact scoring").
#include <cstdint>

#include "trn/limits.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::fixed {

inline constexpr int kWeightBits = 7;
inline constexpr int kWeightOne = 1 << kWeightBits;  // 128: weights are 0..128
inline constexpr int kValueBits = 7;                 // I is in 1/128 grey levels
inline constexpr std::int32_t kMaxValue = 255 << kValueBits;  // 32640
inline constexpr std::int32_t kMaxTemplate = 32767;           // |T| after quantization
// Largest |template value| accepted (float templates): 2^24, where floats stop holding every
// integer; it keeps the host's exact CC / SSD sums in 128 bits (finalize_score).
inline constexpr double kMaxTemplateMagnitude = 16777216.0;

// The per-particle sums are int64: n <= kMaxTemplatePixels samples, each adding at most
// max(|I|, |T|)^2 to sum I^2, sum I*T or sum T^2.
static_assert(double(limits::kMaxTemplatePixels) * double(kMaxTemplate) * double(kMaxTemplate) < 9.2e18,
              "per-particle integer sums could overflow int64 for the largest template");
// ...and the host's 128-bit products of two such sums (n * sum I^2, (sum I)^2) stay far below 2^127.
static_assert(double(limits::kMaxTemplatePixels) * double(limits::kMaxTemplatePixels) * double(kMaxTemplate) *
                      double(kMaxTemplate) < 1.7e38,
              "finalize_score's 128-bit products could overflow");

// Bilinear weight from the exact float fraction f (0 <= f <= 1): round(f * 128), evaluated in float
// as int(f * 128 + 0.5f). f * 128 is exact, so a fused multiply-add gives the same result.
inline int weight(float f) { return static_cast<int>(f * 128.0f + 0.5f); }

// The map value in 1/128 grey levels from the 2x2 cell and the weights.
inline std::int32_t bilinear(int m00, int m10, int m01, int m11, int wx, int wy) {
    const std::int32_t top = m00 * (kWeightOne - wx) + m10 * wx;  // <= 32640
    const std::int32_t bot = m01 * (kWeightOne - wx) + m11 * wx;
    return (top * (kWeightOne - wy) + bot * wy + (1 << (kWeightBits - 1))) >> kWeightBits;
}

}  // namespace trn::fixed
TRN_API_END
