// Device listing and creation for the Vulkan family; see vulkan_family.hpp.
#include "vulkan_family.hpp"

#include "vk_instance.hpp"
#include "vulkan_backend.hpp"

namespace trn {
namespace {

std::vector<DeviceInfo> list_vulkan_devices(const BackendOptions&, std::string& why_none) {
    try {
        const vk::Instance instance(false);
        std::vector<DeviceInfo> out;
        const std::vector<VkPhysicalDevice> devices = instance.physical_devices();
        for (std::size_t i = 0; i < devices.size(); ++i)
            out.push_back(vk::describe_device(instance, devices[i], static_cast<int>(i)).info);
        if (out.empty())
            why_none = "the Vulkan loader reports no devices; install a driver (ICD) such as mesa-vulkan-drivers (lavapipe)";
        return out;
    } catch (const Error& e) {
        why_none = e.what();
        return {};
    }
}

}  // namespace

BackendFamily vulkan_family() {
    return {"vulkan", "Vulkan compute shaders (SPIR-V; lavapipe or any Vulkan 1.1 device)", &list_vulkan_devices,
            [](int index, const BackendOptions& options) { return make_vulkan_backend(index, options.vulkan); }};
}

}  // namespace trn
