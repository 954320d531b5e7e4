// The CUDA backend: NCC scoring with one thread block per particle and 3x3 Sobel over 16-pixel
// strips (kernels/cuda/*.cu, embedded as fat binaries), through the driver API opened at run time.
// One stream per backend; buffers live across calls and only grow; phase times come from CUDA
// events. The planning (arguments, grids, layouts, size checks) is cuda_plan.cpp's.
#include "cuda_backend.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "../common/copy_bandwidth.hpp"
#include "cuda_devices.hpp"
#include "cuda_plan.hpp"
#include "cuda_resources.hpp"
#include "embedded_fatbins.hpp"
#include "trn/impl/cell_mask.hpp"
#include "trn/impl/particle_sums.hpp"

namespace trn::cuda {
namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

class CudaMap : public MapStorage {
public:
    // One byte per pixel, rows packed: what do_upload_map allocates and upload_map's check quotes.
    static std::size_t bytes(std::int64_t w, std::int64_t h) { return std::size_t(w) * std::size_t(h); }
    CudaMap(const Backend* owner, int w, int h, DeviceMemory pixels, DeviceMemory cells, int mask_words)
        : MapStorage(owner, w, h, cells.get() != 0), pixels_(std::move(pixels)), cells_(std::move(cells)), mask_words_(mask_words) {}
    CUdeviceptr pixels() const { return pixels_.get(); }
    CUdeviceptr cells() const { return cells_.get(); }
    int mask_words() const { return mask_words_; }

private:
    DeviceMemory pixels_, cells_;
    int mask_words_;
};

int function_attribute(CUfunction f, CUfunction_attribute a, const char* what) {
    int v = 0;
    check(driver().cuFuncGetAttribute(&v, a, f), std::string("cuFuncGetAttribute(") + what + ")");
    return v;
}

// A host-to-device (or back) copy of a width x height block between two pitches.
CUDA_MEMCPY2D copy_2d(std::size_t width_bytes, std::size_t height) {
    CUDA_MEMCPY2D c;
    std::memset(&c, 0, sizeof c);
    c.WidthInBytes = width_bytes;
    c.Height = height;
    return c;
}

// The events of one call: before upload, before execution, after it, after download.
struct CallEvents {
    explicit CallEvents(const std::shared_ptr<Context>& c) : at{Event(c), Event(c), Event(c), Event(c)} {}
    std::array<Event, 4> at;
};

class CudaBackend final : public Backend, public CopyBandwidthProbe {
public:
    CudaBackend(const DeviceFacts& facts, const BackendOptions::Cuda& options)
        : facts_(facts), info_(describe_device(facts, driver().driver_version)), context_(std::make_shared<Context>(facts.ordinal)),
          stream_(context_), events_(context_) {
        if (facts.warp_size != int(kWarp))
            throw Error("cuda: " + info_.name + " has warps of " + std::to_string(facts.warp_size) +
                        " threads; the kernels' reductions are written for 32");
        const CodeChoice code = code_for_device(embedded_code(), facts.arch);
        if (!code.runs) throw BackendUnavailable(info_.name + " (" + facts.name + "): " + code.text);
        const EmbeddedFatbin ncc = embedded_ncc_score(), sobel = embedded_sobel3x3();
        ncc_module_ = std::make_unique<Module>(context_, ncc.bytes.data(), ncc.file, code.text);
        sobel_module_ = std::make_unique<Module>(context_, sobel.bytes.data(), sobel.file, code.text);
        dense_ = ncc_module_->function("ncc_score_dense");
        sparse_ = ncc_module_->function("ncc_score_sparse");
        sobel_columns_ = sobel_module_->function("sobel3x3_columns");
        sobel_ = sobel_module_->function("sobel3x3");

        // Shapes from what the device and the loaded kernels report (the rule files in backends/common).
        NccDeviceLimits ncc_limits;
        ncc_limits.max_group_size = std::size_t(std::min(
            {facts.max_threads_per_block, function_attribute(dense_, CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK, "ncc_score_dense"),
             function_attribute(sparse_, CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK, "ncc_score_sparse")}));
        ncc_limits.lanes = std::size_t(facts.warp_size);
        ncc_limits.local_memory_bytes = std::size_t(facts.shared_per_block);
        ncc_block_ = ncc_block_size(options.work_group, choose_cuda_ncc_shape(ncc_limits).group_size, ncc_limits.max_group_size);
        sobel_limits_.max_group_size = std::size_t(std::min(
            facts.max_threads_per_block, function_attribute(sobel_, CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK, "sobel3x3")));
        sobel_limits_.lanes = std::size_t(facts.warp_size);
        sobel_limits_.compute_units = std::size_t(facts.multiprocessors);
        sobel_limits_.max_group_y = std::size_t(facts.max_block_dim_y);
        grid_.max_grid_x = std::size_t(facts.max_grid_x);
        grid_.max_grid_y = std::size_t(facts.max_grid_y);
        info_.details += "; NCC block " + std::to_string(ncc_block_) + " threads (" +
                         (options.work_group ? "BackendOptions.cuda.work_group" : "from the warp size and the kernels' limit of " +
                                                                                     std::to_string(ncc_limits.max_group_size)) +
                         "); Sobel blocks from " + std::to_string(sobel_limits_.max_group_size) + " threads max, " +
                         std::to_string(sobel_limits_.compute_units) + " multiprocessors";
    }

    const DeviceInfo& info() const override { return info_; }

protected:
    MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) override {
        const ContextScope scope(*context_);
        const std::size_t bytes = CudaMap::bytes(map.width, map.height);
        const std::size_t mask_bytes = mask ? mask->words.size() * sizeof(std::uint32_t) : 0;
        const std::string what = "upload_map: map " + size_text(map.width, map.height) + " (" + std::to_string(bytes >> 20) + " MiB" +
                                 (mask ? " and its no-data mask" : "") + ")";
        std::size_t free_bytes = 0, total_bytes = 0;
        check(driver().cuMemGetInfo(&free_bytes, &total_bytes), "cuMemGetInfo");
        check_fits(what, bytes + mask_bytes, free_bytes, total_bytes, info_.name + " (" + info_.device + ")");
        DeviceMemory pixels(context_, bytes, "map " + size_text(map.width, map.height));
        DeviceMemory cells;
        check(driver().cuEventRecord(events_.at[0].get(), stream_.get()), "cuEventRecord");
        CUDA_MEMCPY2D c = copy_2d(std::size_t(map.width), std::size_t(map.height));
        c.srcMemoryType = CU_MEMORYTYPE_HOST;
        c.srcHost = map.data;
        c.srcPitch = std::size_t(map.stride);
        c.dstMemoryType = CU_MEMORYTYPE_DEVICE;
        c.dstDevice = pixels.get();
        c.dstPitch = std::size_t(map.width);
        check(driver().cuMemcpy2DAsync(&c, stream_.get()), "cuMemcpy2DAsync(" + what + ") on " + info_.name);
        if (mask) {
            cells = DeviceMemory(context_, mask_bytes, "no-data mask of the map");
            check(driver().cuMemcpyHtoDAsync(cells.get(), mask->words.data(), mask_bytes, stream_.get()),
                  "cuMemcpyHtoDAsync(no-data mask) on " + info_.name);
        }
        check(driver().cuEventRecord(events_.at[1].get(), stream_.get()), "cuEventRecord");
        check(driver().cuStreamSynchronize(stream_.get()), "cuStreamSynchronize(" + what + ") on " + info_.name);
        if (times) times->upload_ms = elapsed_ms(0, 1);
        return std::make_shared<CudaMap>(this, map.width, map.height, std::move(pixels), std::move(cells),
                                         mask ? mask->words_per_row : 0);
    }

    double do_map_bytes(std::int64_t width, std::int64_t height) const override { return double(CudaMap::bytes(width, height)); }

    void do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses, std::span<ParticleScore> out,
                  PhaseTimes* times) override;
    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override;

    // Device-to-device cuMemcpyDtoDAsync between two buffers of `bytes`, each copy timed by events;
    // one untimed copy first (first touch, clocks ramping up).
    CopyBandwidth probe_copy_bandwidth(std::size_t bytes, int repetitions) override {
        const ContextScope scope(*context_);
        std::size_t free_bytes = 0, total_bytes = 0;
        check(driver().cuMemGetInfo(&free_bytes, &total_bytes), "cuMemGetInfo");
        check_fits("measure_copy_bandwidth: two buffers of " + std::to_string(bytes >> 20) + " MiB", 2 * bytes, free_bytes,
                   total_bytes, info_.name);
        const DeviceMemory src(context_, bytes, "copy source"), dst(context_, bytes, "copy destination");
        std::vector<double> seconds;
        for (int i = 0; i <= repetitions; ++i) {
            check(driver().cuEventRecord(events_.at[0].get(), stream_.get()), "cuEventRecord");
            check(driver().cuMemcpyDtoDAsync(dst.get(), src.get(), bytes, stream_.get()), "cuMemcpyDtoDAsync on " + info_.name);
            check(driver().cuEventRecord(events_.at[1].get(), stream_.get()), "cuEventRecord");
            check(driver().cuEventSynchronize(events_.at[1].get()), "cuEventSynchronize(copy)");
            if (i > 0) seconds.push_back(elapsed_ms(0, 1) * 1e-3);
        }
        return copy_bandwidth_from(bytes, std::move(seconds), "cuMemcpyDtoDAsync, CUDA events");
    }

private:
    double elapsed_ms(int from, int to) const {
        float ms = 0;
        check(driver().cuEventElapsedTime(&ms, events_.at[std::size_t(from)].get(), events_.at[std::size_t(to)].get()),
              "cuEventElapsedTime");
        return double(ms);
    }
    void record(int i) { check(driver().cuEventRecord(events_.at[std::size_t(i)].get(), stream_.get()), "cuEventRecord"); }
    void launch(CUfunction f, const char* name, std::size_t gx, std::size_t gy, std::size_t bx, std::size_t by, void* args) {
        void* params[] = {args};
        check(driver().cuLaunchKernel(f, unsigned(gx), unsigned(gy), 1, unsigned(bx), unsigned(by), 1, 0, stream_.get(), params, nullptr),
              std::string("cuLaunchKernel(") + name + ", " + std::to_string(gx) + "x" + std::to_string(gy) + " blocks of " +
                  std::to_string(bx) + "x" + std::to_string(by) + ") on " + info_.name);
    }
    // Uploads the plan's template values (and sparse offsets) unless the device holds exactly these:
    // a particle filter scores many pose batches against one frame.
    void upload_template(const ScoringPlan& plan, const NccLaunch& l);

    DeviceFacts facts_;
    DeviceInfo info_;
    std::shared_ptr<Context> context_;
    Stream stream_;
    CallEvents events_;
    std::unique_ptr<Module> ncc_module_, sobel_module_;
    CUfunction dense_ = nullptr, sparse_ = nullptr, sobel_columns_ = nullptr, sobel_ = nullptr;
    std::size_t ncc_block_ = 0;
    WorkGroupLimits sobel_limits_;
    GridLimits grid_;

    GrowingBuffer affines_, sums_, quantized_, offsets_, sobel_src_, sobel_gx_, sobel_gy_;
    std::vector<float> host_affines_, host_offsets_;
    std::vector<std::int64_t> host_sums_;
    std::vector<std::int32_t> device_quantized_;  // what the device buffers hold now
    std::vector<float> device_offsets_;
};

void CudaBackend::upload_template(const ScoringPlan& plan, const NccLaunch& l) {
    if (quantized_.ensure(context_, l.quantized_bytes, "quantized template")) device_quantized_.clear();
    if (device_quantized_ != plan.quantized) {
        check(driver().cuMemcpyHtoDAsync(quantized_.get(), plan.quantized.data(), l.quantized_bytes, stream_.get()),
              "cuMemcpyHtoDAsync(quantized template) on " + info_.name);
        device_quantized_ = plan.quantized;
    }
    if (plan.dense) return;
    sample_offsets(plan, host_offsets_);
    if (offsets_.ensure(context_, l.offsets_bytes, "sample offsets")) device_offsets_.clear();
    if (device_offsets_ != host_offsets_) {
        check(driver().cuMemcpyHtoDAsync(offsets_.get(), host_offsets_.data(), l.offsets_bytes, stream_.get()),
              "cuMemcpyHtoDAsync(sample offsets) on " + info_.name);
        device_offsets_ = host_offsets_;
    }
}

void CudaBackend::do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                           std::span<ParticleScore> out, PhaseTimes* times) {
    const CudaMap& map = static_cast<const CudaMap&>(storage);
    const std::size_t n = poses.size();
    NccLaunch l = plan_ncc(plan, n, map.width(), map.height(), map.mask_words(), ncc_block_, grid_);
    const ContextScope scope(*context_);
    affines_of(poses.data(), n, host_affines_);
    affines_.ensure(context_, l.affine_bytes, "pose affines");
    sums_.ensure(context_, l.sums_bytes, "particle sums");

    record(0);
    upload_template(plan, l);
    check(driver().cuMemcpyHtoDAsync(affines_.get(), host_affines_.data(), l.affine_bytes, stream_.get()),
          "cuMemcpyHtoDAsync(pose affines) on " + info_.name);
    record(1);
    l.args.map = map.pixels();
    l.args.cells = map.cells();
    l.args.affines = affines_.get();
    l.args.quantized = quantized_.get();
    l.args.offsets = plan.dense ? 0 : offsets_.get();
    l.args.sums = sums_.get();
    const char* name = plan.dense ? "ncc_score_dense" : "ncc_score_sparse";
    launch(plan.dense ? dense_ : sparse_, name, l.grid, 1, l.block, 1, &l.args);
    record(2);
    host_sums_.resize(n * kSumsPerParticle);
    check(driver().cuMemcpyDtoHAsync(host_sums_.data(), sums_.get(), l.sums_bytes, stream_.get()),
          "cuMemcpyDtoHAsync(particle sums) on " + info_.name);
    record(3);
    check(driver().cuStreamSynchronize(stream_.get()), std::string("cuStreamSynchronize(") + name + ", " + std::to_string(n) +
                                                           " particles) on " + info_.name);
    for (std::size_t i = 0; i < n; ++i) {
        const std::int64_t* s = host_sums_.data() + i * kSumsPerParticle;
        out[i] = finalize_score(ParticleSums{s[0], s[1], s[2], s[3], s[4], s[5]}, plan);
    }
    if (times) {
        times->upload_ms = elapsed_ms(0, 1);
        times->execute_ms = elapsed_ms(1, 2);
        times->download_ms = elapsed_ms(2, 3);
    }
}

void CudaBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    const std::size_t w = std::size_t(src.width), h = std::size_t(src.height);
    const std::string what = size_text(src.width, src.height);
    SobelLaunch l = plan_sobel(w, h, sobel_limits_, grid_);
    const ContextScope scope(*context_);
    sobel_src_.ensure(context_, l.src_bytes, "Sobel source");
    sobel_gx_.ensure(context_, l.out_bytes, "Sobel gx");
    sobel_gy_.ensure(context_, l.out_bytes, "Sobel gy");
    l.args.src = sobel_src_.get();
    l.args.gx = sobel_gx_.get();
    l.args.gy = sobel_gy_.get();

    record(0);
    CUDA_MEMCPY2D up = copy_2d(w, h);
    up.srcMemoryType = CU_MEMORYTYPE_HOST;
    up.srcHost = src.data;
    up.srcPitch = std::size_t(src.stride);
    up.dstMemoryType = CU_MEMORYTYPE_DEVICE;
    up.dstDevice = sobel_src_.get();
    up.dstXInBytes = TRN_SOBEL_PAD;
    up.dstPitch = std::size_t(l.args.pitch);
    check(driver().cuMemcpy2DAsync(&up, stream_.get()), "cuMemcpy2DAsync(Sobel source " + what + ") on " + info_.name);
    record(1);
    launch(sobel_columns_, "sobel3x3_columns", l.columns_grid, 1, l.columns_block, 1, &l.args);
    launch(sobel_, "sobel3x3", l.shape.groups_x, l.shape.groups_y, l.shape.group_x, l.shape.group_y, &l.args);
    record(2);
    // Outputs may be ROIs of larger images: the width x height block into their strides.
    for (const auto& [dst, from] : {std::pair{&gx, sobel_gx_.get()}, std::pair{&gy, sobel_gy_.get()}}) {
        CUDA_MEMCPY2D down = copy_2d(w * sizeof(std::int16_t), h);
        down.srcMemoryType = CU_MEMORYTYPE_DEVICE;
        down.srcDevice = from;
        down.srcPitch = std::size_t(l.args.out_pitch) * sizeof(std::int16_t);
        down.dstMemoryType = CU_MEMORYTYPE_HOST;
        down.dstHost = dst->data;
        down.dstPitch = std::size_t(dst->stride) * sizeof(std::int16_t);
        check(driver().cuMemcpy2DAsync(&down, stream_.get()), "cuMemcpy2DAsync(Sobel output " + what + ") on " + info_.name);
    }
    record(3);
    check(driver().cuStreamSynchronize(stream_.get()), "cuStreamSynchronize(sobel3x3, " + what + ") on " + info_.name);
    if (times) {
        times->upload_ms = elapsed_ms(0, 1);
        times->execute_ms = elapsed_ms(1, 2);
        times->download_ms = elapsed_ms(2, 3);
    }
}

}  // namespace

std::unique_ptr<Backend> make_cuda_backend(int index, const BackendOptions::Cuda& options) {
    const std::vector<DeviceFacts> devices = enumerate_devices();
    if (index < 0 || index >= static_cast<int>(devices.size()))
        throw BackendUnavailable("cuda:" + std::to_string(index) + " does not exist (" + std::to_string(devices.size()) +
                                 " CUDA device(s))");
    return std::make_unique<CudaBackend>(devices[std::size_t(index)], options);
}

}  // namespace trn::cuda
