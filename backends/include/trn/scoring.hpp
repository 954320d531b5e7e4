#pragma once
// Everything a caller passes to and gets back from batched particle scoring.
//
// Geometry (identical on every backend):
//   A particle pose is (x, y, yaw, scale): the map-pixel position of the template centre, the
//   heading in radians and the map pixels per template pixel. Template pixel (u, v) with centre
//   c = ((W-1)/2, (H-1)/2) samples the map at
//       (x, y) + scale * R(yaw) * (u - cx, v - cy),   R = [cos -sin; sin cos],
//   so in image coordinates a positive yaw turns the template clockwise on screen. The host turns
//   each pose into six float affine coefficients (see ScoringPlan) and every backend evaluates
//   px = tx + a*du + b*dv, py = ty + c*du + d*dv in float without fused multiply-add, so all
//   backends sample the very same positions.
//   Map pixel centres are at integer coordinates; sampling is bilinear. A sample is valid when
//   0 <= px <= mapW-1 and 0 <= py <= mapH-1 and, for a map uploaded with no-data, the four pixels
//   of its bilinear cell (x0..x0+1, y0..y0+1 below; whatever their weights) are all valid; other
//   samples are skipped, so valid_samples counts the samples used and min_valid_fraction flags a
//   particle mostly over no-data as it flags one mostly off the map.
//
// Exact integer arithmetic (the same bits on every backend; constants in fixed_point.hpp):
//   x0 = min(floor(px), mapW-2), fx = px - x0 (exact in float), wx = int(fx*128 + 0.5f) in 0..128
//   (7-bit weights; likewise y0, wy), and the map value in 1/128 grey levels
//       I = ((m00*(128-wx) + m10*wx)*(128-wy) + (m01*(128-wx) + m11*wx)*wy + 64) >> 7
//   (0..32640; trn::fixed::bilinear). Template values are quantized once on the host (ScoringPlan:
//   T = round((t - offset) * 2^k), |T| <= 32767). Every backend sums n, I, I^2, I*T, T, T^2 over the
//   valid samples in 64-bit integers (exact, so summation order does not matter) and the host turns
//   the sums into scores (finalize_score, 128-bit products), so every backend returns the same bits.
//
// Scores over the valid samples (T = template, I = sampled map, ' = minus the mean):
//   ncc = sum T'I' / sqrt(sum T'^2 * sum I'^2)            (Pearson, dissertation eq. 2.15)
//   cc  = sum T I  / sqrt(sum T^2  * sum I^2)             (eq. 2.14)
//   ssd = 1 - sum (T-I)^2 / sqrt(sum T^2 * sum I^2)       (eq. 2.13)
//
// Invalid particles get every score 0 and a non-zero `flags` (never NaN):
//   too few samples: valid_samples < min_valid_fraction * sample count;
//   flat patch / flat template: variance over the valid samples <= kFlatVariance (grey levels^2,
//   computed from the exact integer sums), which leaves ncc undefined (cc and ssd are then 0 too,
//   for one simple rule).
#include <cstdint>
#include <vector>

#include "trn/timing.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct Pose {
    float x = 0, y = 0, yaw = 0, scale = 1;
};

struct SamplePoint {
    std::int32_t u = 0, v = 0;  // template pixel
};

// Which template pixels take part in the score.
struct Sampling {
    enum class Kind { Dense, Random, Explicit };
    Kind kind = Kind::Dense;
    double fraction = 1.0;          // Random: share of template pixels, (0, 1]
    std::uint64_t seed = 0;         // Random: same seed -> same pixels on every backend
    std::vector<SamplePoint> points;  // Explicit: template pixels, each inside the template

    static Sampling dense() { return {}; }
    static Sampling random(double fraction, std::uint64_t seed) {
        Sampling s;
        s.kind = Kind::Random;
        s.fraction = fraction;
        s.seed = seed;
        return s;
    }
    static Sampling explicit_points(std::vector<SamplePoint> pts) {
        Sampling s;
        s.kind = Kind::Explicit;
        s.points = std::move(pts);
        return s;
    }
};

struct ScoreOptions {
    Sampling sampling;
    double min_valid_fraction = 0.9;  // below this share of valid samples a particle is invalid
};

enum ScoreFlags : std::uint32_t {
    kScoreValid = 0,
    kTooFewSamples = 1u << 0,
    kFlatPatch = 1u << 1,
    kFlatTemplate = 1u << 2,
};

// Variance (in the template's / map's grey-level units squared) at or below which an image is flat.
inline constexpr double kFlatVariance = 1e-4;
// The flatness rule, given n * variance and n.
inline bool is_flat(double n_times_var, double n) { return n_times_var <= n * kFlatVariance; }

struct ParticleScore {
    float ncc = 0;
    float cc = 0;
    float ssd = 0;
    std::uint32_t valid_samples = 0;
    std::uint32_t flags = 0;
    bool valid() const { return flags == kScoreValid; }
};

}  // namespace trn
TRN_API_END
