#include "backend_env.hpp"

#include <cstdlib>
#include <string>

#include "trn/error.hpp"
#include "trn/parse_number.hpp"

namespace trn::cli {
namespace {

// The variable's value, or nullptr when it is unset or empty (both mean "the default").
const char* value_of(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// A whole number in [1, max] (0 would silently mean "the default" in BackendOptions).
std::uint32_t whole_number(const char* name, const char* text, std::uint64_t max) {
    const auto v = parse_whole_number(text);
    if (!v || *v < 1 || *v > max)
        throw Error(std::string(name) + "='" + text + "': expected a whole number from 1 to " + std::to_string(max));
    return static_cast<std::uint32_t>(*v);
}

// The per-user cache root: $XDG_CACHE_HOME, else $HOME/.cache; "" when neither is set.
std::string cache_root() {
    if (const char* xdg = value_of("XDG_CACHE_HOME")) return xdg;
    if (const char* home = value_of("HOME")) return std::string(home) + "/.cache";
    return {};
}

}  // namespace

BackendOptions backend_options_from_environment() {
    BackendOptions o;
    if (const char* d = value_of("TRN_OPENCL_DEVICE")) o.default_device["opencl"] = d;
    if (const char* d = value_of("TRN_VULKAN_DEVICE")) o.default_device["vulkan"] = d;

    if (const char* v = value_of("TRN_CPU_THREADS")) o.cpu.threads = static_cast<int>(whole_number("TRN_CPU_THREADS", v, 4096));
    if (const char* v = value_of("TRN_CPU_SIMD")) o.cpu.simd = std::string(v) != "off";

    if (const char* v = value_of("TRN_OPENCL_WORK_GROUP")) o.opencl.work_group = whole_number("TRN_OPENCL_WORK_GROUP", v, 65536);
    const std::string root = cache_root();
    const char* cl_cache = value_of("TRN_OPENCL_CACHE");
    if (!root.empty() && !(cl_cache && std::string(cl_cache) == "0")) o.opencl.program_cache_dir = root + "/trnkit/opencl";

    if (const char* v = value_of("TRN_VULKAN_WORKGROUP")) o.vulkan.work_group = whole_number("TRN_VULKAN_WORKGROUP", v, 1024);
    if (const char* v = value_of("TRN_VULKAN_PARTICLES_PER_GROUP"))
        o.vulkan.particles_per_group = whole_number("TRN_VULKAN_PARTICLES_PER_GROUP", v, 16);
    if (const char* v = value_of("TRN_VULKAN_MAP_LAYOUT")) o.vulkan.quad_maps = std::string(v) != "bytes";
    if (const char* v = value_of("TRN_VULKAN_NO_SUBGROUPS")) o.vulkan.subgroups = std::string(v) != "1";
    if (const char* v = value_of("TRN_VULKAN_FORCE_STAGING")) o.vulkan.force_staging = std::string(v) == "1";
    if (const char* v = value_of("TRN_VULKAN_VALIDATION")) o.vulkan.validation = std::string(v) == "1";
    // Set but empty: no pipeline cache on disk.
    if (const char* dir = std::getenv("TRN_VULKAN_PIPELINE_CACHE_DIR")) o.vulkan.pipeline_cache_dir = dir;
    else if (!root.empty()) o.vulkan.pipeline_cache_dir = root + "/trnkit";
    return o;
}

}  // namespace trn::cli
