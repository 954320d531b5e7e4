#pragma once
// The host-side preparation shared by every optimized backend: which template pixels are sampled,
// the template values with their mean removed, and the per-pose affine coefficients. Doing this
// once on the host keeps the backends' arithmetic identical (same sample set, same positions).
#include <cstdint>
#include <span>
#include <vector>

#include "trn/scoring.hpp"
#include "trn/template_view.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// px = (tx + a*du) + b*dv ; py = (ty + c*du) + d*dv  with du = u - cx, dv = v - cy (all float,
// evaluated in this order without fused multiply-add).
struct Affine {
    float a, b, c, d, tx, ty;
};
Affine pose_to_affine(const Pose& p);

struct ScoringPlan {
    int width = 0, height = 0;      // template size
    float cx = 0, cy = 0;           // template centre
    bool dense = true;              // all W*H pixels in row-major order, `points` empty
    std::vector<SamplePoint> points;  // sparse: the sampled template pixels (sorted row-major)
    // Template value t of each sample (in sample order) in fixed point: T = round((t - template_offset)
    // * 2^template_exponent), |T| <= fixed::kMaxTemplate, so t ~ template_offset + T / 2^exponent
    // (exact for 8-bit templates: offset is an integer and exponent >= 7).
    std::vector<std::int32_t> quantized;
    double template_offset = 0;     // an integer: the template mean, rounded
    int template_exponent = 7;      // the largest k <= 16 that keeps |T| <= 32767
    double template_mean = 0;       // mean over all samples
    double min_valid_fraction = 0.9;

    std::size_t sample_count() const { return quantized.size(); }
    // Smallest valid-sample count for a valid particle.
    std::uint32_t min_valid_samples() const;
};

// Validates the template and options (throws trn::Error naming the argument) and builds the plan.
ScoringPlan make_scoring_plan(const TemplateView& templ, const ScoreOptions& options);

// The deterministic sparse pixel choice used by Sampling::Kind::Random, exposed for tests.
std::vector<SamplePoint> random_sample_points(int width, int height, double fraction, std::uint64_t seed);

}  // namespace trn
TRN_API_END
