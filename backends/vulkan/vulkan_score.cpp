// Vulkan batched scoring: host-side sample table and affines, one dispatch with one work-group per
// particles_per_group_ particles (ncc_score.comp), then finalize_score on the downloaded sums.
#include <algorithm>
#include <array>
#include <cstring>

#include "../common/ncc_work_shape.hpp"
#include "trn/impl/particle_sums.hpp"
#include "vulkan_backend_impl.hpp"

namespace trn::vk {
namespace {

struct ScorePush {  // matches the push_constant block of ncc_score.comp
    std::uint32_t map_width, map_height, rows_per_chunk, particle_count;
    float cx, cy;
    std::uint32_t mask_words;
};
static_assert(sizeof(ScorePush) == 7 * 4);

struct GroupSums {  // matches GroupSums in ncc_score.comp (std430): 64-bit sums as (low, high) words
    std::uint32_t n, unused;
    std::uint32_t sj[2], sjj[2], sjt[2], st[2], stt[2];
};
static_assert(sizeof(GroupSums) == 48);

std::int64_t join(const std::uint32_t (&w)[2]) {
    return static_cast<std::int64_t>((std::uint64_t(w[1]) << 32) | w[0]);
}

}  // namespace

void VulkanBackend::do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                             std::span<ParticleScore> out, PhaseTimes* times) {
    Context& ctx = *context_;
    const auto& map = static_cast<const VulkanMap&>(storage);
    const std::size_t samples = plan.sample_count(), particles = poses.size();
    const auto& lim = ctx.limits();
    const std::size_t max_groups = std::size_t(lim.maxComputeWorkGroupCount[0]) * lim.maxComputeWorkGroupCount[1];
    // Batches smaller than a group get fewer particles per group (halving, so at most a few
    // pipelines): a group's spare slots repeat its last particle, which is wasted work. (Splitting
    // small batches further so that more lavapipe threads get a group measured no faster.)
    std::uint32_t per_group = particles_per_group_;
    while (per_group > 1 && particles < per_group) per_group /= 2;
    const std::size_t groups = (particles + per_group - 1) / per_group;
    if (groups > max_groups)
        throw Error("score: " + std::to_string(particles) + " poses exceed the " + std::to_string(max_groups) +
                    " work-groups one dispatch on " + info_.name + " may have; score them in batches");
    if (samples > 0xFFFFFFFFu / 8) throw Error("score: the plan has too many samples for " + info_.name);
    if (std::size_t(plan.width) * std::size_t(plan.height) > 0xFFFFFFFFu)
        throw Error("score: a " + std::to_string(plan.width) + "x" + std::to_string(plan.height) + " template is too large for " + info_.name);
    // Large plans take wider groups, so that no invocation outruns lavapipe's loop budget.
    const std::size_t group_size = vulkan_group_for_samples(score_group_size_, samples, score_max_group_);
    if (group_size == 0)
        throw Error("score: the plan's " + std::to_string(samples) + " samples exceed the " +
                    std::to_string(kVulkanMaxSamplesPerItem * score_max_group_) + " one work-group of " + info_.name +
                    " may walk; sample the template sparser");

    const auto t0 = Clock::now();
    // Sample table: quantized template values [S], then for sparse plans the pixel index v*W+u [S].
    const std::size_t table_words = plan.dense ? samples : 2 * samples;
    samples_->ensure(table_words * sizeof(std::uint32_t));
    affines_->ensure(6 * particles * sizeof(float));
    sums_->ensure(particles * sizeof(GroupSums));
    auto* table = static_cast<std::uint32_t*>(samples_->host());
    std::memcpy(table, plan.quantized.data(), samples * sizeof(std::uint32_t));
    if (!plan.dense)
        for (std::size_t k = 0; k < samples; ++k)
            table[samples + k] = static_cast<std::uint32_t>(plan.points[k].v) * static_cast<std::uint32_t>(plan.width) +
                                 static_cast<std::uint32_t>(plan.points[k].u);
    float* affine = static_cast<float*>(affines_->host());
    for (std::size_t i = 0; i < particles; ++i) {
        const Affine A = pose_to_affine(poses[i]);
        const float values[6] = {A.a, A.b, A.c, A.d, A.tx, A.ty};
        std::memcpy(affine + 6 * i, values, sizeof values);
    }
    double upload_ms = ms_since(t0);

    // Bindings 0..2, then binding 3's storage bands and binding 4's texel bands. Unused bands point
    // at the last real one; the layout the map does not use points at stand-ins.
    // Binding 5 (the cell mask) points at the sample table when the map has no no-data (never read).
    std::array<VkBuffer, 4 + kMaxMapChunks> buffers{samples_->device(), affines_->device(), sums_->device()};
    buffers[3 + kMaxMapChunks] = map.masked() ? map.cells->device() : samples_->device();
    std::array<VkBufferView, kMaxMapChunks> views{};
    for (std::uint32_t c = 0; c < kMaxMapChunks; ++c) {
        const std::size_t band = std::min<std::size_t>(c, map.chunks.size() - 1);
        buffers[3 + c] = map.quads ? samples_->device() : map.chunks[band]->device();
        views[c] = map.quads ? map.views[band]->handle() : unused_texel_view_->handle();
    }
    ncc_kernel_->bind(buffers, views);
    // Specialization constants 0..7 of ncc_score.comp.
    const VkPipeline pipeline = ncc_kernel_->pipeline(
        {static_cast<std::uint32_t>(group_size), static_cast<std::uint32_t>(samples), static_cast<std::uint32_t>(map.chunks.size()),
         per_group, static_cast<std::uint32_t>(plan.width), plan.dense ? 1u : 0u, map.quads ? 1u : 0u, map.masked() ? 1u : 0u});
    const ScorePush push{static_cast<std::uint32_t>(map.width()), static_cast<std::uint32_t>(map.height()),
                         map.rows_per_chunk, static_cast<std::uint32_t>(particles), plan.cx, plan.cy, map.mask_words};
    const std::uint32_t gx = static_cast<std::uint32_t>(std::min<std::size_t>(groups, lim.maxComputeWorkGroupCount[0]));
    const std::uint32_t gy = static_cast<std::uint32_t>((groups + gx - 1) / gx);

    VkCommandBuffer cmd = recorder_->begin();
    recorder_->mark(0);
    samples_->record_upload(cmd, table_words * sizeof(std::uint32_t));
    affines_->record_upload(cmd, 6 * particles * sizeof(float));
    barrier_after_upload();
    recorder_->mark(1);
    ncc_kernel_->record_dispatch(cmd, pipeline, &push, gx, gy);
    barrier_after_execute();
    recorder_->mark(2);
    sums_->record_download(cmd, particles * sizeof(GroupSums));
    barrier_after_download();
    recorder_->mark(3);
    const auto t_submit = Clock::now();
    recorder_->submit_and_wait("vkQueueSubmit (score)");
    const double wall_ms = ms_since(t_submit);

    const auto t1 = Clock::now();
    const GroupSums* sums = static_cast<const GroupSums*>(sums_->host());
    for (std::size_t i = 0; i < particles; ++i) {
        const GroupSums& g = sums[i];
        out[i] = finalize_score(ParticleSums{g.n, join(g.sj), join(g.sjj), join(g.sjt), join(g.st), join(g.stt)}, plan);
    }
    if (times) {
        times->upload_ms = upload_ms + recorder_->elapsed_ms(0, 1);
        // Devices without timestamps on this queue get the host's view of the submission.
        times->execute_ms = recorder_->has_timestamps() ? recorder_->elapsed_ms(1, 2) : wall_ms;
        times->download_ms = recorder_->elapsed_ms(2, 3) + ms_since(t1);
    }
    ctx.throw_on_validation_messages("score");
}

}  // namespace trn::vk
