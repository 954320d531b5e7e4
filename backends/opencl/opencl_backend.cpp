// The OpenCL backend: NCC scoring with one work-group per particle and 3x3 Sobel over 16-pixel
// strips (kernels/opencl/*.cl). Buffers live across calls and only grow; phase times come from
// OpenCL profiling events.
#include "opencl_backend.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "../common/copy_bandwidth.hpp"
#include "../common/ncc_work_shape.hpp"
#include "../common/sobel_work_shape.hpp"
#include "../common/pow2.hpp"
#include "device_buffer.hpp"
#include "embedded_kernels.hpp"
#include "trn/impl/cell_mask.hpp"
#include "trn/impl/particle_sums.hpp"
#include "program_cache.hpp"

namespace trn::opencl {
namespace {

constexpr std::size_t kSobelPad = 16;  // TRN_SOBEL_PAD in sobel3x3.cl: bytes left of each source row
constexpr int kSumsPerParticle = 6;    // n, sj, sjj, sjt, st, stt as longs: see ncc_score.cl
constexpr int kAffinePerParticle = 8;  // a, b, c, d, tx, ty, (pad, pad)

double event_ms(cl_event e) {
    cl_ulong start = 0, end = 0;
    check(clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
          "clGetEventProfilingInfo(START)");
    check(clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr), "clGetEventProfilingInfo(END)");
    return end > start ? double(end - start) * 1e-6 : 0.0;
}

// options.work_group (a power of two, for tuning) replaces the default NCC work-group size.
std::optional<std::size_t> work_group_override(const BackendOptions::OpenCl& options) {
    const std::uint32_t v = options.work_group;
    if (v == 0) return std::nullopt;
    if ((v & (v - 1)) != 0 || v > 65536)
        throw Error("BackendOptions.opencl.work_group = " + std::to_string(v) + ": expected a power of two such as 64 or 256");
    return std::size_t(v);
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// The (at most three) writes of one scoring call, kept without allocating.
struct UploadEvents {
    EventHandle events[3];
    int count = 0;
    void add(cl_event e) { events[count++].reset(e); }
};

class OpenClMap : public MapStorage {
public:
    // One buffer of packed rows, one byte per pixel: what do_upload_map allocates and upload_map's
    // limit check quotes (device memory; host memory on CPU devices such as PoCL's).
    static std::size_t bytes(std::int64_t w, std::int64_t h) { return std::size_t(w) * std::size_t(h); }
    OpenClMap(const Backend* owner, int w, int h, MemHandle mem, MemHandle cells, int mask_words)
        : MapStorage(owner, w, h, static_cast<bool>(cells)), mem_(std::move(mem)), cells_(std::move(cells)), mask_words_(mask_words) {}
    cl_mem mem() const { return mem_.get(); }
    cl_mem cells() const { return cells_.get(); }  // the cell mask (masked maps only)
    int mask_words() const { return mask_words_; }  // its words per row; 0 without a mask

private:
    MemHandle mem_, cells_;
    int mask_words_;
};

template <typename T>
void set_arg(cl_kernel k, cl_uint index, const T& value, const char* kernel_name) {
    check(clSetKernelArg(k, index, sizeof(T), &value),
          [&] { return std::string("clSetKernelArg(") + kernel_name + ", argument " + std::to_string(index) + ")"; });
}

KernelHandle make_kernel(cl_program program, const char* name) {
    cl_int err = CL_SUCCESS;
    KernelHandle k(clCreateKernel(program, name, &err));
    check(err, std::string("clCreateKernel(") + name + ")");
    return k;
}

// A compiled kernel may allow smaller work-groups than the device (registers, local memory);
// say so at creation rather than fail every launch with CL_INVALID_WORK_GROUP_SIZE.
void require_work_group(cl_kernel k, const char* name, std::size_t needed) {
    std::size_t allowed = 0;
    cl_device_id device = nullptr;
    cl_program program = nullptr;
    check(clGetKernelInfo(k, CL_KERNEL_PROGRAM, sizeof program, &program, nullptr), "clGetKernelInfo(CL_KERNEL_PROGRAM)");
    check(clGetProgramInfo(program, CL_PROGRAM_DEVICES, sizeof device, &device, nullptr), "clGetProgramInfo(CL_PROGRAM_DEVICES)");
    check(clGetKernelWorkGroupInfo(k, device, CL_KERNEL_WORK_GROUP_SIZE, sizeof allowed, &allowed, nullptr),
          std::string("clGetKernelWorkGroupInfo(") + name + ")");
    if (allowed < needed)
        throw Error(std::string("OpenCL kernel ") + name + " allows work-groups of at most " + std::to_string(allowed) +
                    " on this device but is built for " + std::to_string(needed) +
                    "; set BackendOptions.opencl.work_group (CLI: TRN_OPENCL_WORK_GROUP) to a smaller power of two");
}

// What the device says about running the Sobel kernel (choose_sobel_work_shape picks the shape per call).
WorkGroupLimits sobel_work_group_limits(cl_kernel k, cl_device_id device) {
    WorkGroupLimits limits;
    check(clGetKernelWorkGroupInfo(k, device, CL_KERNEL_WORK_GROUP_SIZE, sizeof limits.max_group_size, &limits.max_group_size,
                                   nullptr),
          "clGetKernelWorkGroupInfo(sobel3x3, CL_KERNEL_WORK_GROUP_SIZE)");
    check(clGetKernelWorkGroupInfo(k, device, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE, sizeof limits.lanes, &limits.lanes,
                                   nullptr),
          "clGetKernelWorkGroupInfo(sobel3x3, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE)");
    limits.compute_units = device_value<cl_uint>(device, CL_DEVICE_MAX_COMPUTE_UNITS);
    return limits;
}

// What the device says that shapes the NCC work-group (choose_opencl_ncc_shape); `lanes` is a
// built kernel's preferred work-group multiple.
NccDeviceLimits ncc_device_limits(cl_device_id device, std::size_t lanes) {
    NccDeviceLimits limits;
    limits.max_group_size = device_value<std::size_t>(device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
    limits.lanes = lanes;
    limits.local_memory_bytes = device_value<cl_ulong>(device, CL_DEVICE_LOCAL_MEM_SIZE);
    limits.local_memory_is_host_memory = device_value<cl_device_local_mem_type>(device, CL_DEVICE_LOCAL_MEM_TYPE) == CL_GLOBAL;
    return limits;
}

class OpenClBackend final : public Backend, public CopyBandwidthProbe {
public:
    OpenClBackend(const DeviceRef& device, int index, const BackendOptions::OpenCl& options)
        : device_(device), info_(describe_device(device, index)) {
        max_alloc_ = device_value<cl_ulong>(device.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);

        cl_int err = CL_SUCCESS;
        context_.reset(clCreateContext(nullptr, 1, &device_.device, nullptr, nullptr, &err));
        check(err, "clCreateContext(" + info_.device + ")");
        queue_.reset(clCreateCommandQueue(context_.get(), device_.device, CL_QUEUE_PROFILING_ENABLE, &err));
        check(err, "clCreateCommandQueue(" + info_.device + ", profiling)");

        // Sobel first: its kernel tells the device's lanes, which shape the NCC program's work-group.
        const ProgramCacheSettings cache = program_cache_settings(options);
        const EmbeddedKernel ncc = embedded_ncc_score(), sobel = embedded_sobel3x3();
        BuiltProgram sobel_program = build_program(context_.get(), device_, sobel.file, sobel.source, sobel.sha256,
                                                   "", cache);
        sobel_program_ = std::move(sobel_program.program);
        sobel_ = make_kernel(sobel_program_.get(), "sobel3x3");
        sobel_columns_ = make_kernel(sobel_program_.get(), "sobel3x3_columns");
        sobel_limits_ = sobel_work_group_limits(sobel_.get(), device_.device);

        const NccDeviceLimits ncc_limits = ncc_device_limits(device_.device, sobel_limits_.lanes);
        wg_size_ = std::min(work_group_override(options).value_or(choose_opencl_ncc_shape(ncc_limits).group_size),
                            floor_pow2(ncc_limits.max_group_size));
        BuiltProgram ncc_program = build_program(context_.get(), device_, ncc.file, ncc.source, ncc.sha256,
                                                 "-DTRN_WG_SIZE=" + std::to_string(wg_size_), cache);
        const bool warm = ncc_program.from_cache && sobel_program.from_cache;
        const double build_ms = ncc_program.build_ms + sobel_program.build_ms;
        record_build_time(cache, device_, warm, build_ms);
        ncc_program_ = std::move(ncc_program.program);
        dense_ = make_kernel(ncc_program_.get(), "ncc_score_dense");
        sparse_ = make_kernel(ncc_program_.get(), "ncc_score_sparse");
        require_work_group(dense_.get(), "ncc_score_dense", wg_size_);
        require_work_group(sparse_.get(), "ncc_score_sparse", wg_size_);
        cl_uint zero = 0;
        no_mask_.reset(clCreateBuffer(context_.get(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof zero, &zero, &err));
        check(err, "clCreateBuffer(no-mask stand-in) on " + info_.name);

        info_.details += "; NCC work-group " + std::to_string(wg_size_) + ", from " + std::to_string(ncc_limits.lanes) +
                         " lanes and " + std::to_string(ncc_limits.local_memory_bytes >> 10) + " KiB local memory " +
                         (ncc_limits.local_memory_is_host_memory ? "in host memory" : "on the device") + "; Sobel work-groups from " +
                         std::to_string(sobel_limits_.max_group_size) + " items max, " + std::to_string(sobel_limits_.lanes) +
                         " lanes, " + std::to_string(sobel_limits_.compute_units) + " compute units; programs " + (warm ? "loaded from the cache" : "built from source") +
                         " in " + std::to_string(static_cast<long>(build_ms + 0.5)) + " ms";
    }

    const DeviceInfo& info() const override { return info_; }

protected:
    MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) override {
        const std::size_t bytes = OpenClMap::bytes(map.width, map.height);
        const std::string what = "map " + size_text(map.width, map.height) + " (" + std::to_string(bytes >> 20) + " MiB)";
        if (bytes > max_alloc_)
            throw Error("upload_map: " + what + " does not fit in one buffer on " + info_.name + " (" + info_.device +
                        "): its largest buffer is " + std::to_string(max_alloc_ >> 20) +
                        " MiB (CL_DEVICE_MAX_MEM_ALLOC_SIZE)");
        cl_int err = CL_SUCCESS;
        MemHandle mem(clCreateBuffer(context_.get(), CL_MEM_READ_ONLY, bytes, nullptr, &err));
        check(err, "clCreateBuffer(" + what + ") on " + info_.name);
        const std::size_t origin[3] = {0, 0, 0};
        const std::size_t region[3] = {std::size_t(map.width), std::size_t(map.height), 1};
        cl_event e = nullptr;
        check(clEnqueueWriteBufferRect(queue_.get(), mem.get(), CL_TRUE, origin, origin, region, std::size_t(map.width), 0,
                                       std::size_t(map.stride), 0, map.data, 0, nullptr, &e),
              [&] { return "clEnqueueWriteBufferRect(" + what + ") on " + info_.name; });
        EventHandle upload(e);
        if (times) times->upload_ms = event_ms(upload.get());
        MemHandle cells;
        if (mask) {
            const std::size_t mask_bytes = mask->words.size() * sizeof(std::uint32_t);
            cells.reset(clCreateBuffer(context_.get(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, mask_bytes,
                                       const_cast<std::uint32_t*>(mask->words.data()), &err));
            check(err, "clCreateBuffer(no-data mask of the " + what + ") on " + info_.name);
        }
        return std::make_shared<OpenClMap>(this, map.width, map.height, std::move(mem), std::move(cells), mask ? mask->words_per_row : 0);
    }

    double do_map_bytes(std::int64_t width, std::int64_t height) const override {
        return double(OpenClMap::bytes(width, height));
    }
    void do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                  std::span<ParticleScore> out, PhaseTimes* times) override;
    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override;

    // Device-to-device clEnqueueCopyBuffer between two buffers of `bytes`, each copy timed by its
    // profiling event; one untimed copy first (first-touch, clocks ramping up).
    CopyBandwidth probe_copy_bandwidth(std::size_t bytes, int repetitions) override {
        if (bytes > max_alloc_)
            throw Error("measure_copy_bandwidth: " + std::to_string(bytes >> 20) + " MiB is more than the largest buffer of " +
                        info_.name + " (" + std::to_string(max_alloc_ >> 20) + " MiB, CL_DEVICE_MAX_MEM_ALLOC_SIZE)");
        cl_int err = CL_SUCCESS;
        MemHandle src(clCreateBuffer(context_.get(), CL_MEM_READ_WRITE, bytes, nullptr, &err));
        check(err, "clCreateBuffer(copy source) on " + info_.name);
        MemHandle dst(clCreateBuffer(context_.get(), CL_MEM_READ_WRITE, bytes, nullptr, &err));
        check(err, "clCreateBuffer(copy destination) on " + info_.name);
        const cl_uchar zero = 0;
        check(clEnqueueFillBuffer(queue_.get(), src.get(), &zero, 1, 0, bytes, 0, nullptr, nullptr), "clEnqueueFillBuffer(copy source)");
        std::vector<double> seconds;
        for (int i = 0; i <= repetitions; ++i) {
            cl_event e = nullptr;
            check(clEnqueueCopyBuffer(queue_.get(), src.get(), dst.get(), 0, 0, bytes, 0, nullptr, &e), "clEnqueueCopyBuffer");
            EventHandle copy(e);
            check(clWaitForEvents(1, &e), "clWaitForEvents(copy)");
            if (i > 0) seconds.push_back(event_ms(copy.get()) * 1e-3);
        }
        return copy_bandwidth_from(bytes, std::move(seconds), "clEnqueueCopyBuffer, profiling events");
    }

private:
    // Uploads the plan's quantized template (and sparse offsets) unless the device already holds
    // exactly these values: a particle filter scores many pose batches against one frame.
    void upload_template(const ScoringPlan& plan, UploadEvents& uploads);

    DeviceRef device_;
    DeviceInfo info_;
    cl_ulong max_alloc_ = 0;
    std::size_t wg_size_ = 0;
    WorkGroupLimits sobel_limits_;
    ContextHandle context_;
    QueueHandle queue_;
    ProgramHandle ncc_program_, sobel_program_;
    KernelHandle dense_, sparse_, sobel_, sobel_columns_;

    DeviceBuffer affines_, sums_, quantized_, offsets_;
    MemHandle no_mask_;  // one word: what the kernels' cell-mask argument points at for maps without no-data
    DeviceBuffer sobel_src_, sobel_gx_, sobel_gy_;
    std::vector<float> host_affines_, host_offsets_;
    std::vector<cl_long> host_sums_;
    std::vector<std::int32_t> device_quantized_;  // what the device buffers hold now
    std::vector<float> device_offsets_;
};

void OpenClBackend::upload_template(const ScoringPlan& plan, UploadEvents& uploads) {
    const std::size_t count = plan.sample_count();
    if (quantized_.ensure(context_.get(), count * sizeof(cl_int), CL_MEM_READ_ONLY, max_alloc_, "quantized template"))
        device_quantized_.clear();
    if (device_quantized_ != plan.quantized) {
        cl_event e = nullptr;
        check(clEnqueueWriteBuffer(queue_.get(), quantized_.get(), CL_FALSE, 0, count * sizeof(cl_int), plan.quantized.data(),
                                   0, nullptr, &e),
              [&] { return "clEnqueueWriteBuffer(quantized template) on " + info_.name; });
        uploads.add(e);
        device_quantized_ = plan.quantized;
    }
    if (plan.dense) return;

    // Same float operations as the dense kernel's (float)u - cx.
    host_offsets_.resize(2 * count);
    for (std::size_t k = 0; k < count; ++k) {
        host_offsets_[2 * k] = float(plan.points[k].u) - plan.cx;
        host_offsets_[2 * k + 1] = float(plan.points[k].v) - plan.cy;
    }
    if (offsets_.ensure(context_.get(), 2 * count * sizeof(float), CL_MEM_READ_ONLY, max_alloc_, "sample offsets"))
        device_offsets_.clear();
    if (device_offsets_ != host_offsets_) {
        cl_event e = nullptr;
        check(clEnqueueWriteBuffer(queue_.get(), offsets_.get(), CL_FALSE, 0, 2 * count * sizeof(float), host_offsets_.data(),
                                   0, nullptr, &e),
              [&] { return "clEnqueueWriteBuffer(sample offsets) on " + info_.name; });
        uploads.add(e);
        device_offsets_ = host_offsets_;
    }
}

void OpenClBackend::do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                             std::span<ParticleScore> out, PhaseTimes* times) {
    const OpenClMap& map = static_cast<const OpenClMap&>(storage);
    const std::size_t n = poses.size();
    if (plan.sample_count() > std::size_t(INT32_MAX) || n > std::size_t(INT32_MAX) / wg_size_)
        throw Error("score: " + std::to_string(n) + " poses x " + std::to_string(plan.sample_count()) +
                    " samples is beyond what the OpenCL kernels index with 32-bit integers");

    host_affines_.resize(n * kAffinePerParticle);
    for (std::size_t i = 0; i < n; ++i) {
        const Affine A = pose_to_affine(poses[i]);
        float* dst = host_affines_.data() + i * kAffinePerParticle;
        dst[0] = A.a, dst[1] = A.b, dst[2] = A.c, dst[3] = A.d, dst[4] = A.tx, dst[5] = A.ty, dst[6] = 0, dst[7] = 0;
    }
    affines_.ensure(context_.get(), n * kAffinePerParticle * sizeof(float), CL_MEM_READ_ONLY, max_alloc_, "pose affines");
    sums_.ensure(context_.get(), n * kSumsPerParticle * sizeof(cl_long), CL_MEM_WRITE_ONLY, max_alloc_, "particle sums");

    UploadEvents uploads;
    upload_template(plan, uploads);
    cl_event e = nullptr;
    check(clEnqueueWriteBuffer(queue_.get(), affines_.get(), CL_FALSE, 0, n * kAffinePerParticle * sizeof(float),
                               host_affines_.data(), 0, nullptr, &e),
          [&] { return "clEnqueueWriteBuffer(pose affines) on " + info_.name; });
    uploads.add(e);

    const cl_mem map_mem = map.mem(), affines = affines_.get(), quantized = quantized_.get(), sums = sums_.get();
    const cl_int map_w = map.width(), map_h = map.height();
    cl_kernel k = plan.dense ? dense_.get() : sparse_.get();
    const char* kname = plan.dense ? "ncc_score_dense" : "ncc_score_sparse";
    const cl_mem cells = map.masked() ? map.cells() : no_mask_.get();
    set_arg(k, 0, map_mem, kname);
    set_arg(k, 1, map_w, kname);
    set_arg(k, 2, map_h, kname);
    set_arg(k, 3, cells, kname);
    set_arg(k, 4, cl_int(map.mask_words()), kname);
    set_arg(k, 5, affines, kname);
    set_arg(k, 6, quantized, kname);
    if (plan.dense) {
        set_arg(k, 7, cl_int(plan.width), kname);
        set_arg(k, 8, cl_int(plan.height), kname);
        set_arg(k, 9, plan.cx, kname);
        set_arg(k, 10, plan.cy, kname);
        set_arg(k, 11, sums, kname);
    } else {
        const cl_mem offsets = offsets_.get();
        set_arg(k, 7, offsets, kname);
        set_arg(k, 8, cl_int(plan.sample_count()), kname);
        set_arg(k, 9, sums, kname);
    }
    const std::size_t global = n * wg_size_, local = wg_size_;
    check(clEnqueueNDRangeKernel(queue_.get(), k, 1, nullptr, &global, &local, 0, nullptr, &e),
          [&] { return std::string("clEnqueueNDRangeKernel(") + kname + ", " + std::to_string(n) + " particles) on " + info_.name; });
    EventHandle execute(e);

    host_sums_.resize(n * kSumsPerParticle);
    check(clEnqueueReadBuffer(queue_.get(), sums, CL_TRUE, 0, n * kSumsPerParticle * sizeof(cl_long), host_sums_.data(), 0,
                              nullptr, &e),
          [&] { return "clEnqueueReadBuffer(particle sums) on " + info_.name; });
    EventHandle download(e);

    for (std::size_t i = 0; i < n; ++i) {
        const cl_long* s = host_sums_.data() + i * kSumsPerParticle;
        out[i] = finalize_score(ParticleSums{s[0], s[1], s[2], s[3], s[4], s[5]}, plan);
    }
    if (times) {
        for (int i = 0; i < uploads.count; ++i) times->upload_ms += event_ms(uploads.events[i].get());
        times->execute_ms = event_ms(execute.get());
        times->download_ms = event_ms(download.get());
    }
}

void OpenClBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    const std::size_t w = std::size_t(src.width), h = std::size_t(src.height);
    const std::string what = size_text(src.width, src.height);
    // Source rows: kSobelPad bytes, the image row, its right neighbour, the last strip's read past
    // it; a multiple of 64 bytes so every strip is an aligned vector. Outputs: whole strips.
    const std::size_t strips = (w + kSobelStripPixels - 1) / kSobelStripPixels;
    const std::size_t pitch = (kSobelPad + strips * kSobelStripPixels + 1 + 63) / 64 * 64;
    const std::size_t out_pitch = strips * kSobelStripPixels;
    sobel_src_.ensure(context_.get(), pitch * h, CL_MEM_READ_WRITE, max_alloc_, "Sobel source");
    sobel_gx_.ensure(context_.get(), out_pitch * h * sizeof(cl_short), CL_MEM_WRITE_ONLY, max_alloc_, "Sobel gx");
    sobel_gy_.ensure(context_.get(), out_pitch * h * sizeof(cl_short), CL_MEM_WRITE_ONLY, max_alloc_, "Sobel gy");

    const std::size_t origin[3] = {0, 0, 0};
    const std::size_t padded_origin[3] = {kSobelPad, 0, 0};
    cl_event e = nullptr;
    const std::size_t src_region[3] = {w, h, 1};
    check(clEnqueueWriteBufferRect(queue_.get(), sobel_src_.get(), CL_FALSE, padded_origin, origin, src_region, pitch, 0,
                                   std::size_t(src.stride), 0, src.data, 0, nullptr, &e),
          [&] { return "clEnqueueWriteBufferRect(Sobel source " + what + ") on " + info_.name; });
    EventHandle upload(e);

    const cl_mem in = sobel_src_.get(), ox = sobel_gx_.get(), oy = sobel_gy_.get();
    const cl_int width = src.width, height = src.height, src_pitch = cl_int(pitch), dst_pitch = cl_int(out_pitch);
    cl_kernel c = sobel_columns_.get();
    set_arg(c, 0, in, "sobel3x3_columns");
    set_arg(c, 1, width, "sobel3x3_columns");
    set_arg(c, 2, height, "sobel3x3_columns");
    set_arg(c, 3, src_pitch, "sobel3x3_columns");
    const std::size_t border_items = 2 * h;
    check(clEnqueueNDRangeKernel(queue_.get(), c, 1, nullptr, &border_items, nullptr, 0, nullptr, &e),
          [&] { return "clEnqueueNDRangeKernel(sobel3x3_columns, " + what + ") on " + info_.name; });
    EventHandle borders(e);

    const SobelWorkShape shape = choose_sobel_work_shape(sobel_limits_, w, h);
    cl_kernel k = sobel_.get();
    set_arg(k, 0, in, "sobel3x3");
    set_arg(k, 1, width, "sobel3x3");
    set_arg(k, 2, height, "sobel3x3");
    set_arg(k, 3, src_pitch, "sobel3x3");
    set_arg(k, 4, cl_int(shape.rows_per_item), "sobel3x3");
    set_arg(k, 5, ox, "sobel3x3");
    set_arg(k, 6, oy, "sobel3x3");
    set_arg(k, 7, dst_pitch, "sobel3x3");
    const std::size_t global[2] = {shape.groups_x * shape.group_x, shape.groups_y * shape.group_y};
    const std::size_t local[2] = {shape.group_x, shape.group_y};
    check(clEnqueueNDRangeKernel(queue_.get(), k, 2, nullptr, global, local, 0, nullptr, &e),
          [&] { return "clEnqueueNDRangeKernel(sobel3x3, " + what + ") on " + info_.name; });
    EventHandle execute(e);

    // Outputs may be ROIs of larger images: copy the WxH block row by row into their strides.
    const std::size_t out_region[3] = {w * sizeof(cl_short), h, 1};
    check(clEnqueueReadBufferRect(queue_.get(), ox, CL_FALSE, origin, origin, out_region, out_pitch * sizeof(cl_short), 0,
                                  std::size_t(gx.stride) * sizeof(cl_short), 0, gx.data, 0, nullptr, &e),
          [&] { return "clEnqueueReadBufferRect(Sobel gx " + what + ") on " + info_.name; });
    EventHandle read_x(e);
    check(clEnqueueReadBufferRect(queue_.get(), oy, CL_TRUE, origin, origin, out_region, out_pitch * sizeof(cl_short), 0,
                                  std::size_t(gy.stride) * sizeof(cl_short), 0, gy.data, 0, nullptr, &e),
          [&] { return "clEnqueueReadBufferRect(Sobel gy " + what + ") on " + info_.name; });
    EventHandle read_y(e);  // blocking, and the queue is in order: both reads are done
    if (times) {
        times->upload_ms = event_ms(upload.get());
        times->execute_ms = event_ms(borders.get()) + event_ms(execute.get());
        times->download_ms = event_ms(read_x.get()) + event_ms(read_y.get());
    }
}

}  // namespace

std::unique_ptr<Backend> make_opencl_backend(const DeviceRef& device, int index, const BackendOptions::OpenCl& options) {
    return std::make_unique<OpenClBackend>(device, index, options);
}

}  // namespace trn::opencl
