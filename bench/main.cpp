// trn_bench: every backend side by side with its OpenCV peers and the STREAM limit, in one run.
// Extra flags (taken out before Google Benchmark parses the rest):
//   --trn_full   the full sweep of issue 6 (default: the quick subset, see sweep.cpp)
// Everything else is Google Benchmark's: --benchmark_filter, --benchmark_out, --benchmark_repetitions ...
#include <benchmark/benchmark.h>
#include <omp.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/ocl.hpp>

#include "devices.hpp"
#include "inputs.hpp"
#include "register.hpp"
#include "sweep.hpp"
#include "trn/error.hpp"

namespace trn::bench {

std::string opencv_opencl_tag() {
    if (!cv::ocl::useOpenCL()) return "OpenCL_OFF";
    const cv::ocl::Device& d = cv::ocl::Device::getDefault();
    const std::string platform = d.vendorName() + " " + d.version();
    std::string lower;
    for (char c : platform + " " + d.name()) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower.find("pocl") != std::string::npos || lower.find("portable") != std::string::npos) return "OpenCL_PoCL";
    std::string tag = "OpenCL_";
    for (char c : d.vendorName())
        if (std::isalnum(static_cast<unsigned char>(c))) tag += c;
    return tag;
}

std::string opencv_opencl_description() {
    if (!cv::ocl::useOpenCL()) return "cv::ocl::useOpenCL() is false: UMat runs on the CPU path";
    const cv::ocl::Device& d = cv::ocl::Device::getDefault();
    return "cv::ocl::useOpenCL() on: " + d.name() + " (" + d.version() + ")";
}

}  // namespace trn::bench

int main(int argc, char** argv) {
    using namespace trn::bench;
    // OpenCV only considers GPUs unless told otherwise; "::" lets it fall back to a CPU OpenCL
    // device (PoCL here), so the UMat peer really runs OpenCL. Must be set before OpenCV's first
    // OpenCL call. An explicit setting by the user is kept.
    setenv("OPENCV_OPENCL_DEVICE", "::", /*overwrite=*/0);
    bool full = false;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--trn_full") == 0) full = true;
        else args.push_back(argv[i]);
    }
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
    try {
        const Sweep sweep = make_sweep(full);
        std::string devices;
        for (const DeviceEntry& d : bench_devices()) devices += (devices.empty() ? "" : ", ") + d.name;
        benchmark::AddCustomContext("trn_sweep", full ? "full" : "quick");
        // The command that produced this run (scripts/bench-report passes its own command line).
        if (const char* cmd = std::getenv("TRN_BENCH_COMMAND"); cmd && *cmd) benchmark::AddCustomContext("trn_command", cmd);
        benchmark::AddCustomContext("trn_devices", devices);
        // Which devices are GPUs (the report's GPU targets apply to those only), and what they are.
        // And the cpu backend's threads and inner loop (AVX2, NEON or portable): with trn_arch below,
        // the row a board's run adds to the platforms' comparison (docs/PLATFORMS.md).
        std::string described, cpu_backend;
        for (const DeviceEntry& d : bench_devices()) {
            described += (described.empty() ? "" : "; ") + d.name + "=" + d.type + "=" + d.device;
            if (d.name == "cpu") cpu_backend = d.details;
        }
        benchmark::AddCustomContext("trn_device_types", described);
        benchmark::AddCustomContext("trn_map", bench_map().source);
        utsname host{};
        benchmark::AddCustomContext("trn_arch", uname(&host) == 0 ? host.machine : "unknown");
        if (!cpu_backend.empty()) benchmark::AddCustomContext("trn_cpu_backend", cpu_backend);
        // OpenMP's wait policy decides whether the cpu backend survives a loaded machine.
        const char* omp_threads = std::getenv("OMP_NUM_THREADS");
        const char* omp_wait = std::getenv("OMP_WAIT_POLICY");
        benchmark::AddCustomContext("trn_openmp", std::to_string(omp_get_max_threads()) + " threads, OMP_NUM_THREADS=" +
                                                       (omp_threads ? omp_threads : "(unset)") + ", OMP_WAIT_POLICY=" +
                                                       (omp_wait ? omp_wait : "(unset)"));
        benchmark::AddCustomContext("trn_cold_working_set_MiB", std::to_string(sweep.cold_bytes >> 20));
        benchmark::AddCustomContext("trn_cold_working_set_basis", sweep.cold_basis);
        benchmark::AddCustomContext("trn_reported_llc_KiB", std::to_string(sysconf(_SC_LEVEL3_CACHE_SIZE) / 1024));
        benchmark::AddCustomContext("trn_opencv", std::string(CV_VERSION) + ", " + opencv_opencl_description());
        register_setup_benchmarks(sweep);  // first, so "first" is the process's first backend creation
        register_stream_benchmarks(sweep);
        register_device_copy_benchmarks(sweep);
        register_sobel_benchmarks(sweep);
        register_ncc_benchmarks(sweep);
        register_latency_benchmarks(sweep);
        const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        if (ran == 0) {  // a filter that matches nothing is a mistake, not a successful run
            std::cerr << "trn_bench: no benchmark matched the filter\n";
            return 1;
        }
    } catch (const trn::Error& e) {
        std::cerr << "trn_bench: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
