#pragma once
// Internal: the Vulkan backend class, shared by vulkan_backend.cpp (setup, maps),
// vulkan_score.cpp and vulkan_sobel.cpp.
#include <chrono>
#include <memory>
#include <vector>

#include "../common/copy_bandwidth.hpp"
#include "../common/sobel_work_shape.hpp"
#include "trn/backend.hpp"
#include "trn/backend_options.hpp"
#include "vk_buffer.hpp"
#include "vk_context.hpp"
#include "vk_pipeline.hpp"
#include "vk_recorder.hpp"

namespace trn::vk {

inline constexpr std::uint32_t kMaxMapChunks = 8;  // TRN_MAX_MAP_CHUNKS in ncc_score.comp

// Most bytes a map may take in the quad layout (4 per pixel, against 1 in the bytes layout); larger
// maps use the bytes layout. 256 MiB keeps maps up to ~8192x8192 on the faster texel fetch while a
// 16384x16384 map takes 256 MiB instead of 1 GiB (measured in docs/RELIABILITY.md).
inline constexpr std::size_t kQuadMapBudget = std::size_t(256) << 20;

// How maps are laid out on the device: the quad budget and the most one band may hold. The backend
// takes them from the device; tests lower them to reach the multi-band paths with small maps.
struct MapPlacement {
    std::size_t quad_budget = kQuadMapBudget;  // bytes of quads, at most
    std::size_t band_quads = 0;                // quads per band (maxTexelBufferElements, <= 1 GiB)
    std::size_t band_bytes = 0;                // bytes per band (maxStorageBufferRange, <= 1 GiB, multiple of 4)
};

// The layout one map gets (map_layout below): quads or bytes, its bands and the bytes they take.
// do_upload_map allocates exactly band_bytes(band_rows(c)) for each band c and upload_map's limit
// check quotes bytes(), so the estimate is the layout's own arithmetic.
struct MapLayout {
    std::size_t width = 0, height = 0;
    bool quads = false;
    std::size_t rows_per_chunk = 0, chunk_count = 0;
    bool rows_too_wide = false;  // bytes layout: a band holds fewer than 3 rows (do_upload_map refuses)
    // Rows of band c: quad rows (no overlap) or pixel rows (one row of overlap with the next band).
    std::size_t band_rows(std::size_t c) const;
    // Bytes of a band of `rows`: a 32-bit word per quad, or four pixels to a word.
    std::size_t band_bytes(std::size_t rows) const;
    // Bytes of every band together.
    double bytes() const;
};
// Quads only while they fit the placement's quad budget in at most kMaxMapChunks bands (and
// quad_maps is on); otherwise bytes, in bands of at most placement.band_bytes. Throws nothing:
// chunk_count may exceed kMaxMapChunks, which do_upload_map refuses by name.
MapLayout map_layout(std::size_t width, std::size_t height, const MapPlacement& placement, bool quad_maps);

// A map on the device as up to kMaxMapChunks row bands (layouts in ncc_score.comp). Quad layout:
// uniform texel buffers (R32_UINT) with a word per pixel holding its 2x2 bilinear footprint, band
// c holds quad rows [c*R, c*R + R), each band within maxTexelBufferElements. Bytes layout (when
// quads would exceed kQuadMapBudget or need too many bands, or BackendOptions.vulkan.quad_maps is off): storage buffers with four
// pixels to a word, band c holds rows [c*R, c*R + R] (one row of overlap), each band within
// maxStorageBufferRange. Keeps the context alive so a map may outlive its backend object safely.
class VulkanMap : public MapStorage {
public:
    VulkanMap(const Backend* owner, std::shared_ptr<Context> context, int width, int height, bool masked)
        : MapStorage(owner, width, height, masked), context(std::move(context)) {}
    std::shared_ptr<Context> context;  // first member: destroyed last
    std::vector<std::unique_ptr<Mirror>> chunks;
    std::vector<std::unique_ptr<TexelView>> views;  // quad layout: one per band (destroyed before the bands)
    std::uint32_t rows_per_chunk = 0;
    bool quads = false;
    std::unique_ptr<Mirror> cells;  // the cell mask (storage buffer) of a masked map
    std::uint32_t mask_words = 0;   // its words per row
};

class VulkanBackend final : public Backend, public CopyBandwidthProbe {
public:
    VulkanBackend(int index, const BackendOptions::Vulkan& options);
    ~VulkanBackend() override;
    const DeviceInfo& info() const override { return info_; }
    const MapPlacement& map_placement() const { return map_placement_; }
    void set_map_placement(const MapPlacement& p) { map_placement_ = p; }  // for tests; values must be > 0

protected:
    MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) override;
    double do_map_bytes(std::int64_t width, std::int64_t height) const override {
        return map_layout(std::size_t(width), std::size_t(height), map_placement_, quad_maps_).bytes();
    }
    void do_score(const MapStorage& map, const ScoringPlan& plan, std::span<const Pose> poses,
                  std::span<ParticleScore> out, PhaseTimes* times) override;
    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override;

public:
    CopyBandwidth probe_copy_bandwidth(std::size_t bytes, int repetitions) override;  // vulkan_copy.cpp

private:
    // Barriers around the transfers of the staging path (no-ops on unified memory).
    void barrier_after_upload();
    void barrier_after_execute();
    void barrier_after_download();

    std::shared_ptr<Context> context_;
    DeviceInfo info_;
    std::unique_ptr<PipelineCache> cache_;
    std::unique_ptr<Recorder> recorder_;
    std::unique_ptr<Kernel> ncc_kernel_, sobel_kernel_;
    std::uint32_t score_group_size_ = 64;
    std::size_t score_max_group_ = 1;  // the widest scoring group this device takes (a power of two)
    std::uint32_t particles_per_group_ = 1;  // at most; see do_score
    WorkGroupLimits sobel_limits_;  // from the device's queries (vulkan_sobel.cpp)
    SobelWorkShape sobel_shape_;    // its work-group (rows per item are chosen per band)
    MapPlacement map_placement_;
    bool quad_maps_ = true;  // false: every map in the bytes layout (BackendOptions.vulkan.quad_maps)
    // Grow-only per-call buffers.
    std::unique_ptr<Mirror> samples_, affines_, sums_;
    // What the binding of the map layout a map does not use points at (every descriptor must be valid).
    std::unique_ptr<Mirror> unused_texels_;
    std::unique_ptr<TexelView> unused_texel_view_;
    std::unique_ptr<Mirror> sobel_src_, sobel_gx_, sobel_gy_;
};

// What the device reports for shaping Sobel work-groups (subgroup size, work-group limits).
WorkGroupLimits sobel_work_group_limits(const Context& ctx);

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace trn::vk
