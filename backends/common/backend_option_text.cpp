#include "trn/backend_option_text.hpp"

#include <cstdint>
#include <utility>

#include "trn/parse_number.hpp"

namespace trn {
namespace {

// A whole number in [1, max] (0 would silently mean "the default" in BackendOptions).
std::uint32_t whole_number(std::string_view name, std::string_view text, std::uint64_t max) {
    const auto v = parse_whole_number(text);
    if (!v || *v < 1 || *v > max)
        throw BackendOptionError(std::string(name), std::string(text), "expected a whole number from 1 to " + std::to_string(max));
    return static_cast<std::uint32_t>(*v);
}

bool on_off(std::string_view name, std::string_view text) {
    if (text == "on" || text == "1" || text == "true") return true;
    if (text == "off" || text == "0" || text == "false") return false;
    throw BackendOptionError(std::string(name), std::string(text), "expected on or off (1 or 0, true or false)");
}

constexpr std::string_view kDefaultDevice = "default_device.";

}  // namespace

BackendOptionError::BackendOptionError(std::string name, std::string value, std::string problem)
    : Error(name + "='" + value + "': " + problem), name_(std::move(name)), value_(std::move(value)), problem_(std::move(problem)) {}

const std::vector<BackendOptionName>& backend_option_names() {
    static const std::vector<BackendOptionName> names = {
        {"default_device.FAMILY", "an index or a device name piece"},
        {"cpu.threads", "1..4096"},
        {"cpu.simd", "on|off"},
        {"opencl.work_group", "1..65536 (a power of two)"},
        {"opencl.program_cache_dir", "a folder (empty: no disk cache)"},
        {"vulkan.work_group", "1..1024 (a power of two)"},
        {"vulkan.particles_per_group", "1..16"},
        {"vulkan.quad_maps", "on|off"},
        {"vulkan.subgroups", "on|off"},
        {"vulkan.force_staging", "on|off"},
        {"vulkan.validation", "on|off"},
        {"vulkan.pipeline_cache_dir", "a folder (empty: no disk cache)"},
        {"cuda.work_group", "1..1024 (a power of two, 32 or more)"},
    };
    return names;
}

void set_backend_option(BackendOptions& o, std::string_view name, std::string_view value) {
    if (name.starts_with(kDefaultDevice) && name.size() > kDefaultDevice.size()) {
        o.default_device[std::string(name.substr(kDefaultDevice.size()))] = std::string(value);
    } else if (name == "cpu.threads") {
        o.cpu.threads = static_cast<int>(whole_number(name, value, 4096));
    } else if (name == "cpu.simd") {
        o.cpu.simd = on_off(name, value);
    } else if (name == "opencl.work_group") {
        o.opencl.work_group = whole_number(name, value, 65536);
    } else if (name == "opencl.program_cache_dir") {
        o.opencl.program_cache_dir = std::string(value);
    } else if (name == "vulkan.work_group") {
        o.vulkan.work_group = whole_number(name, value, 1024);
    } else if (name == "vulkan.particles_per_group") {
        o.vulkan.particles_per_group = whole_number(name, value, 16);
    } else if (name == "vulkan.quad_maps") {
        o.vulkan.quad_maps = on_off(name, value);
    } else if (name == "vulkan.subgroups") {
        o.vulkan.subgroups = on_off(name, value);
    } else if (name == "vulkan.force_staging") {
        o.vulkan.force_staging = on_off(name, value);
    } else if (name == "vulkan.validation") {
        o.vulkan.validation = on_off(name, value);
    } else if (name == "vulkan.pipeline_cache_dir") {
        o.vulkan.pipeline_cache_dir = std::string(value);
    } else if (name == "cuda.work_group") {
        o.cuda.work_group = whole_number(name, value, 1024);
    } else {
        std::string known;
        for (const BackendOptionName& n : backend_option_names()) known += (known.empty() ? "" : ", ") + n.name;
        throw BackendOptionError(std::string(name), std::string(value), "unknown backend option (known: " + known + ")");
    }
}

void set_backend_option(BackendOptions& options, std::string_view assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string_view::npos || eq == 0)
        throw Error("backend option '" + std::string(assignment) + "': expected NAME=VALUE");
    set_backend_option(options, assignment.substr(0, eq), assignment.substr(eq + 1));
}

BackendOptions backend_options_from_variables(const VariableLookup& lookup) {
    auto value_of = [&](const char* name) -> const char* {  // unset and empty both mean "the default"
        const char* v = lookup(name);
        return v && *v ? v : nullptr;
    };
    BackendOptions o;
    for (const auto& [variable, option] : {std::pair{"TRN_OPENCL_DEVICE", "default_device.opencl"},
                                           {"TRN_VULKAN_DEVICE", "default_device.vulkan"},
                                           {"TRN_CUDA_DEVICE", "default_device.cuda"},
                                           {"TRN_CPU_THREADS", "cpu.threads"},
                                           {"TRN_CPU_SIMD", "cpu.simd"},
                                           {"TRN_OPENCL_WORK_GROUP", "opencl.work_group"},
                                           {"TRN_VULKAN_WORKGROUP", "vulkan.work_group"},
                                           {"TRN_VULKAN_PARTICLES_PER_GROUP", "vulkan.particles_per_group"},
                                           {"TRN_CUDA_WORK_GROUP", "cuda.work_group"}}) {
        const char* v = value_of(variable);
        if (!v) continue;
        try {
            set_backend_option(o, option, v);
        } catch (const BackendOptionError& e) {
            throw Error(std::string(variable) + "='" + v + "': " + e.problem());
        }
    }
    // Switches of the test paths: only their one value changes anything.
    if (const char* v = value_of("TRN_VULKAN_MAP_LAYOUT")) o.vulkan.quad_maps = std::string(v) != "bytes";
    if (const char* v = value_of("TRN_VULKAN_NO_SUBGROUPS")) o.vulkan.subgroups = std::string(v) != "1";
    if (const char* v = value_of("TRN_VULKAN_FORCE_STAGING")) o.vulkan.force_staging = std::string(v) == "1";
    if (const char* v = value_of("TRN_VULKAN_VALIDATION")) o.vulkan.validation = std::string(v) == "1";

    std::string root;  // the per-user cache root: $XDG_CACHE_HOME, else $HOME/.cache
    if (const char* xdg = value_of("XDG_CACHE_HOME")) root = xdg;
    else if (const char* home = value_of("HOME")) root = std::string(home) + "/.cache";
    const char* cl_cache = value_of("TRN_OPENCL_CACHE");
    if (!root.empty() && !(cl_cache && std::string(cl_cache) == "0")) o.opencl.program_cache_dir = root + "/trnkit/opencl";
    // Set but empty: no pipeline cache on disk.
    if (const char* dir = lookup("TRN_VULKAN_PIPELINE_CACHE_DIR")) o.vulkan.pipeline_cache_dir = dir;
    else if (!root.empty()) o.vulkan.pipeline_cache_dir = root + "/trnkit";
    return o;
}

}  // namespace trn
