// Scoring plans and batched scoring through the C API (rules: trn/scoring.hpp).
#include <string>
#include <vector>

#include "c_handles.hpp"
#include "c_status.hpp"
#include "trn/limits.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;

namespace {

trn::ScoreOptions to_cxx(const trn_score_options& o) {
    trn::ScoreOptions options;
    options.min_valid_fraction = o.min_valid_fraction;
    const int sampling = trn::capi::raw_enum(o.sampling);
    switch (sampling) {
        case TRN_SAMPLING_DENSE: break;
        case TRN_SAMPLING_RANDOM: options.sampling = trn::Sampling::random(o.fraction, o.seed); break;
        case TRN_SAMPLING_EXPLICIT: {
            if (o.point_count > 0) require_pointer(o.points, "options->points");
            trn::limits::check_count("options->point_count", trn::capi::as_count(o.point_count),
                                     trn::limits::kMaxTemplatePixels, trn::limits::kTemplateBytesPerPixel);
            std::vector<trn::SamplePoint> points(o.point_count);
            for (std::size_t i = 0; i < o.point_count; ++i) points[i] = {o.points[2 * i], o.points[2 * i + 1]};
            options.sampling = trn::Sampling::explicit_points(std::move(points));
            break;
        }
        default: throw InvalidArgument("options->sampling " + std::to_string(sampling) + " is not a trn_sampling_kind");
    }
    return options;
}

}  // namespace

extern "C" {

trn_score_options trn_score_options_default(void) {
    const trn::ScoreOptions cxx;  // the C++ defaults, so the two APIs cannot drift apart
    trn_score_options o{};
    o.sampling = TRN_SAMPLING_DENSE;
    o.fraction = cxx.sampling.fraction;
    o.seed = cxx.sampling.seed;
    o.min_valid_fraction = cxx.min_valid_fraction;
    return o;
}

trn_status trn_plan_create(const trn_template* templ, const trn_score_options* options, trn_plan** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(templ, "templ");
        require_pointer(templ->data, "templ->data");
        if (templ->width <= 0 || templ->height <= 0)
            throw InvalidArgument("template size " + std::to_string(templ->width) + "x" + std::to_string(templ->height) +
                                  " is not positive");
        if (templ->stride < templ->width)
            throw InvalidArgument("template stride " + std::to_string(templ->stride) + " is smaller than its width " +
                                  std::to_string(templ->width));
        trn::TemplateView view;
        const int type = trn::capi::raw_enum(templ->type);
        if (type == TRN_PIXEL_U8)
            view = trn::GrayView{static_cast<const std::uint8_t*>(templ->data), templ->width, templ->height, templ->stride};
        else if (type == TRN_PIXEL_F32)
            view = trn::FloatView{static_cast<const float*>(templ->data), templ->width, templ->height, templ->stride};
        else
            throw InvalidArgument("templ->type " + std::to_string(type) + " is not a trn_pixel_type");
        const trn_score_options defaults = trn_score_options_default();
        auto plan = std::make_unique<trn_plan>();
        plan->plan = trn::make_scoring_plan(view, to_cxx(options ? *options : defaults));
        *out = plan.release();
    });
}

size_t trn_plan_sample_count(const trn_plan* plan) { return plan ? plan->plan.sample_count() : 0; }

void trn_plan_destroy(trn_plan* plan) { delete plan; }

trn_status trn_score_poses(trn_backend* backend, const trn_map* map, const trn_plan* plan, const trn_pose* poses, size_t count,
                           trn_score* out, trn_times* times) {
    return guarded(__func__, [&] {
        require_pointer(backend, "backend");
        require_pointer(map, "map");
        require_pointer(plan, "plan");
        if (count > 0) require_pointer(poses, "poses"), require_pointer(out, "out");
        // Before the copies below, so an absurd count is refused by name rather than by bad_alloc.
        trn::limits::check_count("count", trn::capi::as_count(count), trn::limits::kMaxParticles, trn::limits::kParticleBytes);
        std::vector<trn::Pose> cxx_poses(count);
        for (std::size_t i = 0; i < count; ++i) cxx_poses[i] = {poses[i].x, poses[i].y, poses[i].yaw, poses[i].scale};
        std::vector<trn::ParticleScore> scores(count);
        trn::PhaseTimes t;
        backend->impl->score(map->handle, plan->plan, cxx_poses, scores, &t);
        for (std::size_t i = 0; i < count; ++i) out[i] = {scores[i].ncc, scores[i].cc, scores[i].ssd, scores[i].valid_samples, scores[i].flags};
        if (times) *times = {t.upload_ms, t.execute_ms, t.download_ms};
    });
}

}  // extern "C"
