#pragma once
// The TRN_* variables -> trn::BackendOptions for the test and benchmark mains, read the way the
// trnkit CLI reads them (apps/trnkit/backend_env.cpp, the table in README.md), so that
// `TRN_OPENCL_DEVICE=1 ctest` and `TRN_VULKAN_VALIDATION=1 trn_bench` mean what they mean for the
// CLI. The values are parsed by the library (trn/backend_option_text.hpp); only the getenv is here.
#include <cstdlib>
#include <string>

#include "trn/backend_option_text.hpp"
#include "trn/error.hpp"

namespace trn::test {

inline BackendOptions backend_options_from_environment() {
    auto value_of = [](const char* name) -> const char* {
        const char* v = std::getenv(name);
        return v && *v ? v : nullptr;
    };
    BackendOptions o;
    for (const auto& [variable, option] : {std::pair{"TRN_OPENCL_DEVICE", "default_device.opencl"},
                                           {"TRN_VULKAN_DEVICE", "default_device.vulkan"},
                                           {"TRN_CPU_THREADS", "cpu.threads"},
                                           {"TRN_CPU_SIMD", "cpu.simd"},
                                           {"TRN_OPENCL_WORK_GROUP", "opencl.work_group"},
                                           {"TRN_VULKAN_WORKGROUP", "vulkan.work_group"},
                                           {"TRN_VULKAN_PARTICLES_PER_GROUP", "vulkan.particles_per_group"}}) {
        if (const char* v = value_of(variable)) {
            try {
                set_backend_option(o, option, v);
            } catch (const BackendOptionError& e) {
                throw Error(std::string(variable) + "='" + v + "': " + e.problem());
            }
        }
    }
    if (const char* v = value_of("TRN_VULKAN_MAP_LAYOUT")) o.vulkan.quad_maps = std::string(v) != "bytes";
    if (const char* v = value_of("TRN_VULKAN_NO_SUBGROUPS")) o.vulkan.subgroups = std::string(v) != "1";
    if (const char* v = value_of("TRN_VULKAN_FORCE_STAGING")) o.vulkan.force_staging = std::string(v) == "1";
    if (const char* v = value_of("TRN_VULKAN_VALIDATION")) o.vulkan.validation = std::string(v) == "1";

    std::string root;  // $XDG_CACHE_HOME, else $HOME/.cache
    if (const char* xdg = value_of("XDG_CACHE_HOME")) root = xdg;
    else if (const char* home = value_of("HOME")) root = std::string(home) + "/.cache";
    const char* cl_cache = value_of("TRN_OPENCL_CACHE");
    if (!root.empty() && !(cl_cache && std::string(cl_cache) == "0")) o.opencl.program_cache_dir = root + "/trnkit/opencl";
    if (const char* dir = std::getenv("TRN_VULKAN_PIPELINE_CACHE_DIR")) o.vulkan.pipeline_cache_dir = dir;
    else if (!root.empty()) o.vulkan.pipeline_cache_dir = root + "/trnkit";
    return o;
}

}  // namespace trn::test
