// Host-side preparation of a scoring call; see scoring_plan.hpp.
#include "trn/impl/particle_sums.hpp"
#include "trn/scoring_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "trn/detail/splitmix.hpp"
#include "trn/error.hpp"
#include "trn/fixed_point.hpp"
#include "trn/limits.hpp"

namespace trn {

Affine pose_to_affine(const Pose& p) {
    const double c = std::cos(static_cast<double>(p.yaw)) * p.scale;
    const double s = std::sin(static_cast<double>(p.yaw)) * p.scale;
    return {static_cast<float>(c), static_cast<float>(-s), static_cast<float>(s), static_cast<float>(c), p.x, p.y};
}

std::uint32_t ScoringPlan::min_valid_samples() const {
    return static_cast<std::uint32_t>(std::ceil(min_valid_fraction * static_cast<double>(sample_count()) - 1e-9));
}

namespace {

// T = round((t - offset) * 2^k): offset = the rounded mean (an integer, so 8-bit templates stay
// exact), k the largest exponent <= 16 with max |t - offset| * 2^k <= 32767 (>= -11 for |t| <= 2^24).
void quantize_template(const std::vector<double>& values, ScoringPlan& plan) {
    plan.template_offset = std::round(plan.template_mean);
    double spread = 0;
    for (double v : values) spread = std::max(spread, std::fabs(v - plan.template_offset));  // exact in double
    int k = 16;
    while (k > -64 && std::ldexp(spread, k) > fixed::kMaxTemplate) --k;
    plan.template_exponent = k;
    plan.quantized.resize(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        plan.quantized[i] = static_cast<std::int32_t>(std::llround(std::ldexp(values[i] - plan.template_offset, k)));
}

}  // namespace

std::vector<SamplePoint> random_sample_points(int width, int height, double fraction, std::uint64_t seed) {
    const std::size_t total = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const std::size_t count = std::clamp<std::size_t>(static_cast<std::size_t>(std::llround(fraction * total)), 1, total);
    // Partial Fisher-Yates over pixel indices; sorted afterwards for memory locality.
    std::vector<std::uint32_t> idx(total);
    std::iota(idx.begin(), idx.end(), 0u);
    std::uint64_t state = seed;
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t j = i + splitmix::next64(state) % (total - i);
        std::swap(idx[i], idx[j]);
    }
    idx.resize(count);
    std::sort(idx.begin(), idx.end());
    std::vector<SamplePoint> pts(count);
    for (std::size_t i = 0; i < count; ++i)
        pts[i] = {static_cast<std::int32_t>(idx[i] % width), static_cast<std::int32_t>(idx[i] / width)};
    return pts;
}

ScoringPlan make_scoring_plan(const TemplateView& templ, const ScoreOptions& options) {
    if (templ.data == nullptr || templ.width <= 0 || templ.height <= 0)
        throw Error("score: template is empty");
    if (templ.stride < templ.width)
        throw Error("score: template stride " + std::to_string(templ.stride) + " is smaller than its width " +
                    std::to_string(templ.width));
    limits::check_image("score: template", templ.width, templ.height, limits::kMaxTemplatePixels,
                        limits::kTemplateBytesPerPixel);
    if (!(options.min_valid_fraction >= 0.0 && options.min_valid_fraction <= 1.0))
        throw Error("score: min_valid_fraction " + std::to_string(options.min_valid_fraction) +
                    " is outside [0, 1]");

    ScoringPlan plan;
    plan.width = templ.width;
    plan.height = templ.height;
    plan.cx = static_cast<float>((templ.width - 1) / 2.0);
    plan.cy = static_cast<float>((templ.height - 1) / 2.0);
    plan.min_valid_fraction = options.min_valid_fraction;

    const Sampling& s = options.sampling;
    switch (s.kind) {
        case Sampling::Kind::Dense:
            break;
        case Sampling::Kind::Random:
            if (!(s.fraction > 0.0 && s.fraction <= 1.0))
                throw Error("score: sampling fraction " + std::to_string(s.fraction) + " is outside (0, 1]");
            plan.dense = false;
            plan.points = random_sample_points(templ.width, templ.height, s.fraction, s.seed);
            break;
        case Sampling::Kind::Explicit:
            if (s.points.empty()) throw Error("score: explicit sampling has no points");
            limits::check_count("score: explicit sample count", static_cast<std::int64_t>(s.points.size()),
                                limits::kMaxTemplatePixels, limits::kTemplateBytesPerPixel);
            for (std::size_t i = 0; i < s.points.size(); ++i) {
                const SamplePoint& p = s.points[i];
                if (p.u < 0 || p.v < 0 || p.u >= templ.width || p.v >= templ.height)
                    throw Error("score: sample point " + std::to_string(i) + " (" + std::to_string(p.u) + ", " +
                                std::to_string(p.v) + ") is outside the template");
            }
            plan.dense = false;
            plan.points = s.points;
            break;
    }

    std::vector<double> values;
    if (plan.dense) {
        values.reserve(static_cast<std::size_t>(templ.width) * templ.height);
        for (int v = 0; v < templ.height; ++v)
            for (int u = 0; u < templ.width; ++u) values.push_back(templ.at(u, v));
    } else {
        values.reserve(plan.points.size());
        for (const SamplePoint& p : plan.points) values.push_back(templ.at(p.u, p.v));
    }
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]) || std::fabs(values[i]) > fixed::kMaxTemplateMagnitude)
            throw Error("score: template sample " + std::to_string(i) + " (" + std::to_string(values[i]) + ") is " +
                        (std::isfinite(values[i]) ? "beyond +-16777216 (2^24), the largest template value exact scoring takes"
                                                  : "not finite"));
    plan.template_mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    quantize_template(values, plan);
    return plan;
}

namespace {

__extension__ using Wide = __int128;  // GCC and Clang on 64-bit targets

Wide pow2(int e) { return Wide(1) << e; }

}  // namespace

// Everything is computed from the exact integer sums: the variances and covariance as 128-bit
// integers (n * sum - sum * sum, no cancellation error), then one double division per score.
// CC and SSD need the raw template values t = offset + T / 2^k and map values i = I / 128; both
// are integers in units of 2^-e with e = max(k, 7), so their sums are exact 128-bit integers too
// (|offset * 2^e| <= 2^40, so n * (offset * 2^e)^2 <= 2^104).
ParticleScore finalize_score(const ParticleSums& s, const ScoringPlan& plan) {
    ParticleScore r;
    r.valid_samples = static_cast<std::uint32_t>(s.n);
    if (s.n <= 0 || r.valid_samples < plan.min_valid_samples()) {
        r.flags = kTooFewSamples;
        return r;
    }
    const Wide n = s.n;
    const Wide var_i = n * s.sjj - Wide(s.sj) * s.sj;  // n^2 * variance, in (1/128 grey)^2
    const Wide var_t = n * s.stt - Wide(s.st) * s.st;  // n^2 * variance, in (2^-k grey)^2
    const Wide cov = n * s.sjt - Wide(s.sj) * s.st;
    const double nd = static_cast<double>(s.n), k = plan.template_exponent;
    // n * variance in grey levels^2, for the flatness rule.
    if (is_flat(std::ldexp(static_cast<double>(var_t), -2 * int(k)) / nd, nd)) r.flags |= kFlatTemplate;
    if (is_flat(std::ldexp(static_cast<double>(var_i), -2 * fixed::kValueBits) / nd, nd)) r.flags |= kFlatPatch;
    if (r.flags) return r;
    const double ncc = static_cast<double>(cov) / std::sqrt(static_cast<double>(var_i) * static_cast<double>(var_t));

    const int e = std::max(plan.template_exponent, fixed::kValueBits);
    const Wide a = static_cast<Wide>(plan.template_offset) * pow2(e);  // offset in units of 2^-e
    const Wide ts = pow2(e - plan.template_exponent), is = pow2(e - fixed::kValueBits);
    const Wide sum_tt = n * a * a + 2 * a * (s.st * ts) + Wide(s.stt) * ts * ts;
    const Wide sum_ii = Wide(s.sjj) * is * is;
    const Wide sum_ti = a * (s.sj * is) + Wide(s.sjt) * ts * is;
    const Wide sum_dd = sum_tt - 2 * sum_ti + sum_ii;  // sum (t - i)^2, exactly
    const double norm = std::sqrt(static_cast<double>(sum_tt) * static_cast<double>(sum_ii));
    r.ncc = static_cast<float>(std::clamp(ncc, -1.0, 1.0));
    r.cc = norm > 0 ? static_cast<float>(static_cast<double>(sum_ti) / norm) : 0.0f;
    r.ssd = norm > 0 ? static_cast<float>(1.0 - static_cast<double>(sum_dd) / norm) : 0.0f;
    return r;
}

}  // namespace trn
