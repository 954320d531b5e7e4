// Host-side preparation of a scoring call; see scoring_plan.hpp.
#include "trn/impl/particle_sums.hpp"
#include "trn/scoring_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "trn/error.hpp"
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

// SplitMix64: tiny, fast, and the same sequence on every platform.
std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
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
        const std::size_t j = i + splitmix64(state) % (total - i);
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
        if (!std::isfinite(values[i])) throw Error("score: template sample " + std::to_string(i) + " is not finite");
    plan.template_mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    plan.centered.resize(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        plan.centered[i] = static_cast<float>(values[i] - plan.template_mean);
    return plan;
}

ParticleScore finalize_score(const ParticleSums& s, const ScoringPlan& plan) {
    ParticleScore r;
    r.valid_samples = static_cast<std::uint32_t>(s.n);
    if (s.n <= 0 || r.valid_samples < plan.min_valid_samples()) {
        r.flags = kTooFewSamples;
        return r;
    }
    const double n = s.n;
    const double var_j = s.sjj - s.sj * s.sj / n;  // n * variance of the patch
    const double var_t = s.stt - s.st * s.st / n;  // n * variance of the template over valid samples
    if (is_flat(var_t, n, s.st / n)) r.flags |= kFlatTemplate;
    if (is_flat(var_j, n, s.sj / n + s.shift)) r.flags |= kFlatPatch;
    if (r.flags) return r;

    const double ncc = (s.sjt - s.sj * s.st / n) / std::sqrt(var_j * var_t);
    // Raw sums for CC and SSD from the shifted / centred ones.
    const double mt = plan.template_mean, k = s.shift;
    const double sum_tt = s.stt + 2 * mt * s.st + n * mt * mt;
    const double sum_i = s.sj + n * k;
    const double sum_ii = s.sjj + 2 * k * s.sj + n * k * k;
    const double sum_ti = s.sjt + k * s.st + mt * sum_i;
    const double norm = std::sqrt(sum_tt * sum_ii);
    r.ncc = static_cast<float>(std::clamp(ncc, -1.0, 1.0));
    r.cc = norm > 0 ? static_cast<float>(sum_ti / norm) : 0.0f;
    r.ssd = norm > 0 ? static_cast<float>(1.0 - (sum_tt - 2 * sum_ti + sum_ii) / norm) : 0.0f;
    return r;
}

}  // namespace trn
