#include "backend_env.hpp"

#include <cstdlib>
#include <string>

#include "trn/backend_option_text.hpp"
#include "trn/error.hpp"

namespace trn::cli {
namespace {

// The variable's value, or nullptr when it is unset or empty (both mean "the default").
const char* value_of(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// Sets `option` from the variable when it is set; a refused value names the variable.
void take(BackendOptions& o, const char* variable, const char* option) {
    const char* v = value_of(variable);
    if (!v) return;
    try {
        set_backend_option(o, option, v);
    } catch (const BackendOptionError& e) {
        throw Error(std::string(variable) + "='" + v + "': " + e.problem());
    }
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
    take(o, "TRN_OPENCL_DEVICE", "default_device.opencl");
    take(o, "TRN_VULKAN_DEVICE", "default_device.vulkan");
    take(o, "TRN_CPU_THREADS", "cpu.threads");
    take(o, "TRN_CPU_SIMD", "cpu.simd");
    take(o, "TRN_OPENCL_WORK_GROUP", "opencl.work_group");
    take(o, "TRN_VULKAN_WORKGROUP", "vulkan.work_group");
    take(o, "TRN_VULKAN_PARTICLES_PER_GROUP", "vulkan.particles_per_group");
    // Switches of the test paths: only their one value changes anything.
    if (const char* v = value_of("TRN_VULKAN_MAP_LAYOUT")) o.vulkan.quad_maps = std::string(v) != "bytes";
    if (const char* v = value_of("TRN_VULKAN_NO_SUBGROUPS")) o.vulkan.subgroups = std::string(v) != "1";
    if (const char* v = value_of("TRN_VULKAN_FORCE_STAGING")) o.vulkan.force_staging = std::string(v) == "1";
    if (const char* v = value_of("TRN_VULKAN_VALIDATION")) o.vulkan.validation = std::string(v) == "1";

    const std::string root = cache_root();
    const char* cl_cache = value_of("TRN_OPENCL_CACHE");
    if (!root.empty() && !(cl_cache && std::string(cl_cache) == "0")) o.opencl.program_cache_dir = root + "/trnkit/opencl";
    // Set but empty: no pipeline cache on disk.
    if (const char* dir = std::getenv("TRN_VULKAN_PIPELINE_CACHE_DIR")) o.vulkan.pipeline_cache_dir = dir;
    else if (!root.empty()) o.vulkan.pipeline_cache_dir = root + "/trnkit";
    return o;
}

}  // namespace trn::cli
