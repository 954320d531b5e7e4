// The families this build was configured with. New backends add one line here (and their
// TRN_HAVE_* define in CMake); nothing registers itself behind the reader's back.
#include "../cpu/cpu_backend.hpp"
#include "../cpu_ref/cpu_ref_backend.hpp"
#include "trn/registry.hpp"
#ifdef TRN_HAVE_OPENCL
#include "../opencl/opencl_family.hpp"
#endif
#ifdef TRN_HAVE_VULKAN
#include "../vulkan/vulkan_family.hpp"
#endif
#ifdef TRN_HAVE_CUDA
#include "../cuda/cuda_family.hpp"
#elif !defined(TRN_CUDA_MISSING)
#define TRN_CUDA_MISSING "the CUDA backend was not configured"  // backends/cuda/CMakeLists.txt sets the reason
#endif

namespace trn {
namespace {

BackendFamily single_device_family(std::string name, std::string description,
                                   std::function<std::unique_ptr<Backend>(const BackendOptions&)> make) {
    return {std::move(name), std::move(description),
            [make](const BackendOptions& options, std::string&) { return std::vector<DeviceInfo>{make(options)->info()}; },
            [make](int, const BackendOptions& options) { return make(options); }};
}

// Listed so that `trnkit devices` and the tests say by name what this build lacks.
[[maybe_unused]] BackendFamily not_built_family(std::string name, std::string description, std::string why) {
    return {std::move(name), std::move(description),
            [why](const BackendOptions&, std::string& why_none) {
                why_none = why;
                return std::vector<DeviceInfo>{};
            },
            [](int, const BackendOptions&) -> std::unique_ptr<Backend> { throw BackendUnavailable("backend not built"); }};
}

BackendRegistry build_default_registry() {
    BackendRegistry r;
    r.add(single_device_family("cpu-ref", "naive reference (the test oracle)",
                               [](const BackendOptions&) { return make_cpu_ref_backend(); }));
    r.add(single_device_family("cpu", "optimized CPU",
                               [](const BackendOptions& options) { return make_cpu_backend(options.cpu); }));
#ifdef TRN_HAVE_OPENCL
    r.add(opencl_family());
#else
    r.add(not_built_family("opencl", "OpenCL C kernels", "not built: OpenCL headers or ICD loader were not found at configure time"));
#endif
#ifdef TRN_HAVE_VULKAN
    r.add(vulkan_family());
#else
    r.add(not_built_family("vulkan", "Vulkan compute shaders", "not built: Vulkan headers, loader or glslangValidator were not found at configure time"));
#endif
#ifdef TRN_HAVE_CUDA
    r.add(cuda_family());
#else
    r.add(not_built_family("cuda", "CUDA kernels", "built without CUDA (" TRN_CUDA_MISSING ")"));
#endif
    return r;
}

}  // namespace

const BackendRegistry& default_registry() {
    static const BackendRegistry registry = build_default_registry();
    return registry;
}

}  // namespace trn
