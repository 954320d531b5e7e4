// Vulkan backend: device setup, kernels and map upload. Scoring is in vulkan_score.cpp, Sobel in
// vulkan_sobel.cpp.
#include "vulkan_backend.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>

#include "ncc_score_shared.h"
#include "../common/ncc_work_shape.hpp"
#include "../common/pow2.hpp"
#include "ncc_score_subgroup.h"
#include "sobel3x3.h"
#include "trn/impl/cell_mask.hpp"
#include "vulkan_backend_impl.hpp"

namespace trn {
namespace vk {
namespace {

// What the device says that shapes the scoring work-group (choose_vulkan_ncc_shape).
NccDeviceLimits ncc_device_limits(const Context& ctx) {
    const auto& lim = ctx.limits();
    NccDeviceLimits limits;
    limits.max_group_size = ctx.max_linear_group();
    limits.lanes = ctx.subgroup_lanes();
    limits.local_memory_bytes = lim.maxComputeSharedMemorySize;
    // No memory of its own: every memory type is host memory as seen by the host's caches.
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    const VkPhysicalDeviceMemoryProperties& m = ctx.physical().memory;
    limits.local_memory_is_host_memory = m.memoryTypeCount > 0;
    for (std::uint32_t i = 0; i < m.memoryTypeCount; ++i)
        if ((m.memoryTypes[i].propertyFlags & host) != host) limits.local_memory_is_host_memory = false;
    return limits;
}

// The device's shape, with options.work_group (a power of two <= kVulkanMaxScoreGroup) and
// options.particles_per_group (1..16) replacing its parts when set (for tuning); the group always
// within the device limits.
NccWorkShape choose_score_shape(const Context& ctx, const BackendOptions::Vulkan& options) {
    const NccDeviceLimits limits = ncc_device_limits(ctx);
    NccWorkShape shape = choose_vulkan_ncc_shape(limits);
    if (const std::uint32_t v = options.work_group; v != 0) {
        if (v > kVulkanMaxScoreGroup || (v & (v - 1)) != 0)
            throw Error("vulkan: BackendOptions.vulkan.work_group = " + std::to_string(v) + " is not a power of two in [1, " +
                        std::to_string(kVulkanMaxScoreGroup) + "]");
        shape.group_size = v;
    }
    if (const std::uint32_t v = options.particles_per_group; v != 0) {
        if (v > 16)
            throw Error("vulkan: BackendOptions.vulkan.particles_per_group = " + std::to_string(v) + " is not in [1, 16]");
        shape.particles_per_group = v;
    }
    shape.group_size = floor_pow2(std::min(shape.group_size, limits.max_group_size));
    return shape;
}

}  // namespace

VulkanBackend::VulkanBackend(int index, const BackendOptions::Vulkan& options)
    : context_(std::make_shared<Context>(std::make_unique<Instance>(options.validation), index, options.force_staging)),
      quad_maps_(options.quad_maps) {
    Context& ctx = *context_;
    info_ = ctx.physical().info;
    info_.details += std::string(", ") + (ctx.unified_memory() ? "unified memory (mapped device buffers)" : "staging buffers");
    cache_ = std::make_unique<PipelineCache>(ctx, options.pipeline_cache_dir);
    recorder_ = std::make_unique<Recorder>(ctx);

    // options.subgroups = false forces the shared-memory reduction (to test it on any device).
    const bool subgroups = ctx.physical().subgroup_arithmetic() && options.subgroups;
    const std::span<const std::uint32_t> ncc_code =
        subgroups ? std::span<const std::uint32_t>(ncc_score_subgroup) : std::span<const std::uint32_t>(ncc_score_shared);
    // Bindings: sample table, affines, sums, map bands (bytes layout), map bands (quad layout), cell mask.
    using Kind = Binding::Kind;
    ncc_kernel_ = std::make_unique<Kernel>(
        ctx, *cache_, ncc_code, subgroups ? "ncc_score (subgroup reduction)" : "ncc_score (shared-memory reduction)",
        std::vector<Binding>{{Kind::StorageBuffer, 1}, {Kind::StorageBuffer, 1}, {Kind::StorageBuffer, 1},
                             {Kind::StorageBuffer, kMaxMapChunks}, {Kind::UniformTexelBuffer, kMaxMapChunks},
                             {Kind::StorageBuffer, 1}},
        7 * sizeof(std::uint32_t));
    sobel_kernel_ = std::make_unique<Kernel>(ctx, *cache_, std::span<const std::uint32_t>(sobel3x3), "sobel3x3",
                                             std::vector<Binding>(3), 5 * sizeof(std::uint32_t));
    // Bytes one map band may hold: the storage-buffer range (bytes layout) or texel-buffer elements
    // (quad layout), capped at 1 GiB per allocation.
    constexpr std::size_t kMaxAllocation = std::size_t(1) << 30;
    map_placement_.band_bytes = std::min<std::size_t>(ctx.limits().maxStorageBufferRange, kMaxAllocation) & ~std::size_t(3);
    map_placement_.band_quads = std::min<std::size_t>(ctx.limits().maxTexelBufferElements, kMaxAllocation / 4);
    const NccWorkShape score_shape = choose_score_shape(ctx, options);
    score_group_size_ = static_cast<std::uint32_t>(score_shape.group_size);
    // Large plans widen the group up to this (vulkan_group_for_samples, per call).
    score_max_group_ = floor_pow2(std::min(ncc_device_limits(ctx).max_group_size, kVulkanMaxScoreGroup));
    particles_per_group_ = static_cast<std::uint32_t>(score_shape.particles_per_group);
    sobel_limits_ = sobel_work_group_limits(ctx);
    sobel_shape_ = choose_sobel_work_shape(sobel_limits_, kSobelStripPixels, 1);  // the group; rows per item vary per call
    info_.details += ", scoring work-group " + std::to_string(score_group_size_) + " for up to " +
                     std::to_string(particles_per_group_) + " particle(s)" +
                     (subgroups ? " with subgroup reduction" : " with shared-memory reduction") + ", Sobel work-group " +
                     std::to_string(sobel_shape_.group_x) + "x" + std::to_string(sobel_shape_.group_y);

    samples_ = std::make_unique<Mirror>(ctx, "the template sample table");
    affines_ = std::make_unique<Mirror>(ctx, "the particle affines");
    sums_ = std::make_unique<Mirror>(ctx, "the particle sums");
    sobel_src_ = std::make_unique<Mirror>(ctx, "the Sobel source band");
    sobel_gx_ = std::make_unique<Mirror>(ctx, "the Sobel gx band");
    sobel_gy_ = std::make_unique<Mirror>(ctx, "the Sobel gy band");
    unused_texels_ = std::make_unique<Mirror>(ctx, "the unused texel binding", VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    unused_texels_->ensure(4);
    unused_texel_view_ = std::make_unique<TexelView>(ctx, unused_texels_->device(), VK_FORMAT_R32_UINT, 4);
    ctx.throw_on_validation_messages("creating the Vulkan backend");
}

VulkanBackend::~VulkanBackend() = default;

void VulkanBackend::barrier_after_upload() {
    if (!context_->unified_memory())
        recorder_->barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                           VK_ACCESS_SHADER_READ_BIT);
}

void VulkanBackend::barrier_after_execute() {
    if (context_->unified_memory())
        recorder_->barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                           VK_ACCESS_HOST_READ_BIT);
    else
        recorder_->barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_READ_BIT);
}

void VulkanBackend::barrier_after_download() {
    if (!context_->unified_memory())
        recorder_->barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                           VK_ACCESS_HOST_READ_BIT);
}

MapLayout map_layout(std::size_t w, std::size_t h, const MapPlacement& placement, bool quad_maps) {
    MapLayout layout;
    layout.width = w, layout.height = h;
    const std::size_t max_bytes = placement.band_bytes, max_quads = placement.band_quads;
    // Quads: H-1 quad rows of W words, no overlap; only while they fit the quad budget.
    const std::size_t quad_rows_per_band = max_quads / w;
    layout.quads = quad_maps && 4 * w * (h - 1) <= placement.quad_budget && quad_rows_per_band > 0 &&
                   (h - 1 + quad_rows_per_band - 1) / quad_rows_per_band <= kMaxMapChunks;
    layout.rows_per_chunk = layout.quads ? std::min(h - 1, quad_rows_per_band) : h;
    layout.chunk_count = 1;
    if (layout.quads) {
        layout.chunk_count = (h - 1 + layout.rows_per_chunk - 1) / layout.rows_per_chunk;
    } else if (layout.band_bytes(h) > max_bytes) {
        if (max_bytes / w < 3) {
            layout.rows_too_wide = true;
            return layout;
        }
        layout.rows_per_chunk = max_bytes / w - 1;  // plus one overlap row
        layout.chunk_count = (h - 2) / layout.rows_per_chunk + 1;
    }
    return layout;
}

std::size_t MapLayout::band_rows(std::size_t c) const {
    const std::size_t first = c * rows_per_chunk;
    return quads ? std::min(rows_per_chunk, height - 1 - first) : std::min(rows_per_chunk + 1, height - first);
}

std::size_t MapLayout::band_bytes(std::size_t rows) const {
    return quads ? rows * width * 4 : (rows * width + 3) & ~std::size_t(3);
}

double MapLayout::bytes() const {
    if (rows_too_wide || chunk_count > kMaxMapChunks)  // refused anyway; the pixels once, as a figure for the message
        return double(width) * double(height);
    double total = 0;
    for (std::size_t c = 0; c < chunk_count; ++c) total += double(band_bytes(band_rows(c)));
    return total;
}

MapHandle VulkanBackend::do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) {
    Context& ctx = *context_;
    const std::size_t w = static_cast<std::size_t>(map.width), h = static_cast<std::size_t>(map.height);
    auto handle = std::make_shared<VulkanMap>(this, context_, map.width, map.height, mask != nullptr);
    if (mask) {  // one storage buffer, before the bands: a refusal costs no upload
        const std::size_t bytes = mask->words.size() * sizeof(std::uint32_t);
        if (bytes > ctx.limits().maxStorageBufferRange)
            throw Error("upload_map: the no-data mask of map " + std::to_string(w) + "x" + std::to_string(h) + " takes " +
                        std::to_string(bytes >> 20) + " MiB, more than one storage buffer on " + info_.name + " (" +
                        std::to_string(ctx.limits().maxStorageBufferRange >> 20) + " MiB, maxStorageBufferRange)");
        const auto t0 = Clock::now();
        handle->cells = std::make_unique<Mirror>(ctx, "the no-data mask", VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        handle->cells->ensure(bytes);
        std::memcpy(handle->cells->host(), mask->words.data(), bytes);
        const double host_ms = ms_since(t0);
        VkCommandBuffer cmd = recorder_->begin();
        recorder_->mark(0);
        handle->cells->record_upload(cmd, bytes);
        recorder_->mark(1);
        barrier_after_upload();
        recorder_->submit_and_wait("vkQueueSubmit (no-data mask upload)");
        handle->cells->drop_staging();
        handle->mask_words = static_cast<std::uint32_t>(mask->words_per_row);
        if (times) times->upload_ms += host_ms + recorder_->elapsed_ms(0, 1);
    }
    const MapLayout layout = map_layout(w, h, map_placement_, quad_maps_);
    const bool quads = layout.quads;
    const std::size_t rows_per_chunk = layout.rows_per_chunk, chunk_count = layout.chunk_count;
    if (layout.rows_too_wide)
        throw Error("upload_map: map rows of " + std::to_string(w) + " pixels are too wide for " + info_.name);
    if (chunk_count > kMaxMapChunks)
        throw Error("upload_map: map " + std::to_string(w) + "x" + std::to_string(h) + " needs " +
                    std::to_string(chunk_count) + " bands of " + std::to_string(map_placement_.band_bytes) + " bytes on " +
                    info_.name + " (maxStorageBufferRange); at most " + std::to_string(kMaxMapChunks) + " are supported");
    handle->rows_per_chunk = static_cast<std::uint32_t>(rows_per_chunk);
    handle->quads = quads;

    // One submission per band, so that on staging devices at most one band's staging copy exists at
    // a time (host memory: the map plus one band, not the map plus all of them).
    double host_ms = 0, device_ms = 0;
    for (std::size_t c = 0; c < chunk_count; ++c) {
        const auto t0 = Clock::now();
        const std::size_t first = c * rows_per_chunk;
        const std::size_t rows = layout.band_rows(c);
        auto chunk = std::make_unique<Mirror>(ctx, "a map band", quads ? VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT
                                                                      : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        chunk->ensure(layout.band_bytes(rows));
        if (quads) {
            auto* dst = static_cast<std::uint32_t*>(chunk->host());
            for (std::size_t y = 0; y < rows; ++y) {
                const std::uint8_t* top = map.row(static_cast<int>(first + y));
                const std::uint8_t* bottom = map.row(static_cast<int>(first + y + 1));
                std::uint32_t* out = dst + y * w;
                for (std::size_t x = 0; x + 1 < w; ++x)
                    out[x] = std::uint32_t(top[x]) | std::uint32_t(top[x + 1]) << 8 | std::uint32_t(bottom[x]) << 16 |
                             std::uint32_t(bottom[x + 1]) << 24;
                out[w - 1] = 0;  // the last column starts no 2x2 footprint
            }
        } else {
            auto* dst = static_cast<std::uint8_t*>(chunk->host());
            for (std::size_t y = 0; y < rows; ++y) std::memcpy(dst + y * w, map.row(static_cast<int>(first + y)), w);
        }
        host_ms += ms_since(t0);
        VkCommandBuffer cmd = recorder_->begin();
        recorder_->mark(0);
        chunk->record_upload(cmd, layout.band_bytes(rows));
        recorder_->mark(1);
        barrier_after_upload();
        recorder_->submit_and_wait("vkQueueSubmit (map upload)");
        chunk->drop_staging();
        device_ms += recorder_->elapsed_ms(0, 1);
        if (quads) handle->views.push_back(std::make_unique<TexelView>(ctx, chunk->device(), VK_FORMAT_R32_UINT, layout.band_bytes(rows)));
        handle->chunks.push_back(std::move(chunk));
    }
    if (times) times->upload_ms += host_ms + device_ms;
    ctx.throw_on_validation_messages("upload_map");
    return handle;
}

}  // namespace vk

std::unique_ptr<Backend> make_vulkan_backend(int index, const BackendOptions::Vulkan& options) {
    return std::make_unique<vk::VulkanBackend>(index, options);
}

}  // namespace trn
