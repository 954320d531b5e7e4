// Sobel on every backend and on OpenCV (cv::Mat and cv::UMat), hot and cold.
// Names: sobel/<WxH>/<hot|cold|batch16>/<dev:NAME | peer:NAME>.
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>

#include <opencv2/core.hpp>
#include <opencv2/core/ocl.hpp>
#include <opencv2/imgproc.hpp>

#include "devices.hpp"
#include "inputs.hpp"
#include "register.hpp"
#include "timing.hpp"

namespace trn::bench {
namespace {

enum class Warmth { Hot, Cold, Batch16 };
const char* warmth_text(Warmth w) { return w == Warmth::Hot ? "hot" : w == Warmth::Cold ? "cold" : "batch16"; }

// Cold frames are large (the rotating set exceeds the LLC), so one set is kept and reused by
// every benchmark of the same size instead of being rebuilt for each.
SobelFrames& frames_for(const FrameSize& size, Warmth warmth, std::size_t cold_bytes) {
    static std::optional<SobelFrames> slots[3];
    std::optional<SobelFrames>& slot = slots[static_cast<int>(warmth)];
    if (!slot || slot->size.width != size.width || slot->size.height != size.height) {
        slot.reset();  // free the old set before building the next
        slot = warmth == Warmth::Hot    ? frame_set(size, 1)
               : warmth == Warmth::Cold ? cold_frames(size, cold_bytes)
                                        : frame_set(size, 16);
    }
    return *slot;
}

int frames_per_iteration(Warmth w) { return w == Warmth::Batch16 ? 16 : 1; }

void sobel_on_device(benchmark::State& state, DeviceEntry dev, FrameSize size, Warmth warmth, std::size_t cold_bytes) {
    Backend& backend = backend_for(dev.name);
    SobelFrames& f = frames_for(size, warmth, cold_bytes);
    const int w = size.width, h = size.height;
    auto call = [&](int k, PhaseTimes* t) {
        backend.sobel({f.src_at(k), w, h, w}, {f.gx_at(k), w, h, w}, {f.gy_at(k), w, h, w}, t);
    };
    PhaseTimes t;
    if (first_time("sobel/" + dev.name + "/" + size.text())) call(f.next(), &t);  // lazy buffers, launch setup
    const bool device_clock = has_device_clock(dev.family);
    const int per_iter = frames_per_iteration(warmth);
    IterationLog log(state);
    for (auto _ : state) {
        PhaseTimes sum;
        const auto t0 = Clock::now();
        for (int b = 0; b < per_iter; ++b) {
            call(f.next(), &t);
            sum.upload_ms += t.upload_ms, sum.execute_ms += t.execute_ms, sum.download_ms += t.download_ms;
        }
        log.add(seconds_since(t0), sum, device_clock);
    }
    const double px = double(w) * h * per_iter;
    log.finish(px * kSobelBytesPerPixel, px, "Mpix/s", 1e6);
    state.SetLabel(backend.info().device + (warmth == Warmth::Cold ? ", " + std::to_string(f.count) + " frames rotating" : ""));
}

void cv_sobel_pair(const cv::Mat& src, cv::Mat& gx, cv::Mat& gy) {
    cv::Sobel(src, gx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101);
    cv::Sobel(src, gy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REFLECT_101);
}

void sobel_cv_mat(benchmark::State& state, FrameSize size, Warmth warmth, std::size_t cold_bytes) {
    SobelFrames& f = frames_for(size, warmth, cold_bytes);
    const int w = size.width, h = size.height;
    auto mats = [&](int k) {
        return std::tuple{cv::Mat(h, w, CV_8UC1, const_cast<std::uint8_t*>(f.src_at(k))), cv::Mat(h, w, CV_16SC1, f.gx_at(k)),
                          cv::Mat(h, w, CV_16SC1, f.gy_at(k))};
    };
    if (first_time("sobel/cv_Mat/" + size.text())) {
        auto [s, x, y] = mats(f.next());
        cv_sobel_pair(s, x, y);
    }
    IterationLog log(state);
    for (auto _ : state) {
        auto [s, x, y] = mats(f.next());
        const auto t0 = Clock::now();
        cv_sobel_pair(s, x, y);
        log.add(seconds_since(t0));
    }
    const double px = double(w) * h;
    log.finish(px * kSobelBytesPerPixel, px, "Mpix/s", 1e6);
    state.SetLabel("OpenCV " CV_VERSION ", " + std::to_string(cv::getNumThreads()) + " threads" +
                   (warmth == Warmth::Cold ? ", " + std::to_string(f.count) + " frames rotating" : ""));
}

// End to end as a UMat user sees it: upload, both gradients, read back into host memory.
void sobel_cv_umat(benchmark::State& state, FrameSize size, Warmth warmth, std::size_t cold_bytes) {
    SobelFrames& f = frames_for(size, warmth, cold_bytes);
    const int w = size.width, h = size.height;
    cv::UMat usrc, ugx, ugy;
    auto run = [&](int k) {
        cv::Mat(h, w, CV_8UC1, const_cast<std::uint8_t*>(f.src_at(k))).copyTo(usrc);
        cv::Sobel(usrc, ugx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101);
        cv::Sobel(usrc, ugy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REFLECT_101);
        cv::Mat gx(h, w, CV_16SC1, f.gx_at(k)), gy(h, w, CV_16SC1, f.gy_at(k));
        ugx.copyTo(gx);  // blocking read: the work is finished when this returns
        ugy.copyTo(gy);
    };
    run(f.next());  // builds OpenCV's OpenCL kernels (first time) and sizes this call's UMats
    IterationLog log(state);
    for (auto _ : state) {
        const int k = f.next();
        const auto t0 = Clock::now();
        run(k);
        log.add(seconds_since(t0));
    }
    const double px = double(w) * h;
    log.finish(px * kSobelBytesPerPixel, px, "Mpix/s", 1e6);
    state.SetLabel(opencv_opencl_description() + (warmth == Warmth::Cold ? ", " + std::to_string(f.count) + " frames rotating" : ""));
}

std::string case_name(const FrameSize& s, Warmth w, const std::string& who) {
    return "sobel/" + s.text() + "/" + warmth_text(w) + "/" + who;
}

void register_case(const Sweep& sweep, const FrameSize& size, Warmth warmth) {
    const bool is_reference_size = size.width == sweep.sobel_reference_size.width && size.height == sweep.sobel_reference_size.height;
    for (const DeviceEntry& dev : bench_devices()) {
        if (dev.family == "cpu-ref" && (!is_reference_size || warmth != Warmth::Hot)) continue;
        if (warmth == Warmth::Batch16 && !has_device_clock(dev.family)) continue;
        benchmark::RegisterBenchmark(case_name(size, warmth, "dev:" + dev.name).c_str(), sobel_on_device, dev, size, warmth,
                                     sweep.cold_bytes)
            ->UseManualTime()->Unit(benchmark::kMillisecond);
    }
    if (warmth == Warmth::Batch16) return;
    benchmark::RegisterBenchmark(case_name(size, warmth, "peer:cv_Sobel_Mat").c_str(), sobel_cv_mat, size, warmth, sweep.cold_bytes)
        ->UseManualTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(case_name(size, warmth, "peer:cv_Sobel_UMat_" + opencv_opencl_tag()).c_str(), sobel_cv_umat, size,
                                 warmth, sweep.cold_bytes)
        ->UseManualTime()->Unit(benchmark::kMillisecond);
}

}  // namespace

void register_sobel_benchmarks(const Sweep& sweep) {
    for (const FrameSize& s : sweep.sobel_sizes) register_case(sweep, s, Warmth::Hot);
    for (const FrameSize& s : sweep.sobel_cold_sizes) register_case(sweep, s, Warmth::Cold);
    if (sweep.sobel_batch16)
        for (const FrameSize& s : sweep.sobel_sizes) register_case(sweep, s, Warmth::Batch16);
}

}  // namespace trn::bench
