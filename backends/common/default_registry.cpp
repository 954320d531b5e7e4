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

namespace trn {
namespace {

BackendFamily single_device_family(std::unique_ptr<Backend> (*make)(), std::string description) {
    const DeviceInfo info = make()->info();
    return {info.family, std::move(description),
            [info](std::string&) { return std::vector<DeviceInfo>{info}; },
            [make](int) { return make(); }, ""};
}

// Listed so that `trnkit devices` and the tests say by name what this build lacks.
[[maybe_unused]] BackendFamily not_built_family(std::string name, std::string description, std::string why) {
    return {std::move(name), std::move(description),
            [why](std::string& why_none) {
                why_none = why;
                return std::vector<DeviceInfo>{};
            },
            [](int) -> std::unique_ptr<Backend> { throw BackendUnavailable("backend not built"); }, ""};
}

BackendRegistry build_default_registry() {
    BackendRegistry r;
    r.add(single_device_family(&make_cpu_ref_backend, "naive reference (the test oracle)"));
    r.add(single_device_family(&make_cpu_backend, "optimized CPU"));
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
    return r;
}

}  // namespace

const BackendRegistry& default_registry() {
    static const BackendRegistry registry = build_default_registry();
    return registry;
}

}  // namespace trn
