// Run-time loading of the Vulkan loader library; see vk_api.hpp.
#include "vk_api.hpp"

#include <dlfcn.h>

#include "trn/error.hpp"

namespace trn::vk {
namespace {

LoaderApi open_loader() {
    void* lib = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char* why = dlerror();
        throw BackendUnavailable(std::string("the Vulkan loader libvulkan.so.1 could not be loaded (") +
                                 (why ? why : "unknown reason") + "); install libvulkan1 and a driver such as mesa-vulkan-drivers");
    }
    LoaderApi api;
    api.vkGetInstanceProcAddr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(lib, "vkGetInstanceProcAddr"));
    if (!api.vkGetInstanceProcAddr)
        throw BackendUnavailable("libvulkan.so.1 has no vkGetInstanceProcAddr; the Vulkan loader is broken");
    auto global = [&](const char* name) { return api.vkGetInstanceProcAddr(VK_NULL_HANDLE, name); };
    api.vkCreateInstance = reinterpret_cast<PFN_vkCreateInstance>(global("vkCreateInstance"));
    api.vkEnumerateInstanceLayerProperties =
        reinterpret_cast<PFN_vkEnumerateInstanceLayerProperties>(global("vkEnumerateInstanceLayerProperties"));
    api.vkEnumerateInstanceExtensionProperties =
        reinterpret_cast<PFN_vkEnumerateInstanceExtensionProperties>(global("vkEnumerateInstanceExtensionProperties"));
    api.vkEnumerateInstanceVersion = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(global("vkEnumerateInstanceVersion"));
    if (!api.vkCreateInstance || !api.vkEnumerateInstanceLayerProperties || !api.vkEnumerateInstanceExtensionProperties)
        throw BackendUnavailable("the Vulkan loader lacks vkCreateInstance or the enumeration calls");
    return api;  // the library stays loaded for the life of the process
}

}  // namespace

const LoaderApi& loader() {
    static const LoaderApi api = open_loader();
    return api;
}

InstanceApi load_instance_api(VkInstance instance) {
    InstanceApi api;
    const auto get = loader().vkGetInstanceProcAddr;
#define TRN_VK_LOAD(name) api.name = reinterpret_cast<PFN_##name>(get(instance, #name));
    TRN_VK_INSTANCE_FUNCTIONS(TRN_VK_LOAD)
#undef TRN_VK_LOAD
#define TRN_VK_REQUIRE(name) \
    if (!api.name && std::string_view(#name).find("DebugUtils") == std::string_view::npos) \
        throw Error("vulkan: the loader returned no " #name " (Vulkan 1.1 is required)");
    TRN_VK_INSTANCE_FUNCTIONS(TRN_VK_REQUIRE)
#undef TRN_VK_REQUIRE
    return api;
}

const char* result_name(VkResult r) {
    switch (r) {
#define TRN_VK_CASE(x) case x: return #x;
        TRN_VK_CASE(VK_SUCCESS) TRN_VK_CASE(VK_NOT_READY) TRN_VK_CASE(VK_TIMEOUT) TRN_VK_CASE(VK_INCOMPLETE)
        TRN_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY) TRN_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        TRN_VK_CASE(VK_ERROR_INITIALIZATION_FAILED) TRN_VK_CASE(VK_ERROR_DEVICE_LOST)
        TRN_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED) TRN_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        TRN_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT) TRN_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        TRN_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER) TRN_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        TRN_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED) TRN_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
        TRN_VK_CASE(VK_ERROR_UNKNOWN) TRN_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        TRN_VK_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef TRN_VK_CASE
        default: return "VkResult (unnamed)";
    }
}

void check(VkResult r, const char* call) {
    if (r == VK_SUCCESS) return;
    std::string msg = std::string("vulkan: ") + call + " failed: " + result_name(r) + " (" + std::to_string(int(r)) + ")";
    if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
        msg += "; the device ran out of memory - use a smaller map, template or particle batch";
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        msg += "; no Vulkan driver (ICD) is installed - install mesa-vulkan-drivers or a GPU driver";
    throw Error(msg);
}

}  // namespace trn::vk
