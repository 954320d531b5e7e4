// Vulkan instance creation, validation messenger and device description; see vk_instance.hpp.
#include "vk_instance.hpp"

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>

namespace trn::vk {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    static_cast<MessageLog*>(user)->add(std::string("validation ") + level + ": " +
                                        (data && data->pMessage ? data->pMessage : "(no text)"));
    return VK_FALSE;
}

bool has_layer(const char* name) {
    std::uint32_t count = 0;
    check(loader().vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(count);
    check(loader().vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

std::string version_text(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

const char* type_name(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "gpu";
        default: return "other";
    }
}

}  // namespace

void MessageLog::add(std::string message) {
    std::lock_guard lock(mutex_);
    messages_.push_back(std::move(message));
}

std::vector<std::string> MessageLog::take() {
    std::lock_guard lock(mutex_);
    return std::exchange(messages_, {});
}

Instance::Instance(bool validation) {
    const LoaderApi& l = loader();
    std::uint32_t loader_version = VK_API_VERSION_1_0;
    if (l.vkEnumerateInstanceVersion) l.vkEnumerateInstanceVersion(&loader_version);
    if (loader_version < VK_API_VERSION_1_1)
        throw BackendUnavailable("the Vulkan loader supports only Vulkan " + version_text(loader_version) +
                                 "; trnkit needs 1.1 or newer");

    std::vector<const char*> layers, extensions;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = &on_message;
    messenger_info.pUserData = log_.get();
    if (validation) {
        if (!has_layer("VK_LAYER_KHRONOS_validation"))
            throw Error("vulkan: TRN_VULKAN_VALIDATION=1 but the layer VK_LAYER_KHRONOS_validation is not installed "
                        "(install vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "trnkit";
    app.pEngineName = "trnkit";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (validation) info.pNext = &messenger_info;  // also reports on vkCreateInstance / vkDestroyInstance
    const VkResult r = l.vkCreateInstance(&info, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw BackendUnavailable("no ICD: the Vulkan loader found no driver (no ICD JSON in its search folders or in VK_DRIVER_FILES); install mesa-vulkan-drivers (lavapipe) or a GPU driver");
    if (r == VK_ERROR_EXTENSION_NOT_PRESENT && validation)
        throw Error("vulkan: TRN_VULKAN_VALIDATION=1 but VK_EXT_debug_utils is not available");
    check(r, "vkCreateInstance");
    api_ = load_instance_api(instance_);
    if (validation) {
        if (!api_.vkCreateDebugUtilsMessengerEXT) {
            api_.vkDestroyInstance(instance_, nullptr);
            throw Error("vulkan: TRN_VULKAN_VALIDATION=1 but vkCreateDebugUtilsMessengerEXT is missing");
        }
        check(api_.vkCreateDebugUtilsMessengerEXT(instance_, &messenger_info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
}

Instance::~Instance() {
    if (messenger_) api_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
    if (instance_) api_.vkDestroyInstance(instance_, nullptr);
}

std::vector<VkPhysicalDevice> Instance::physical_devices() const {
    std::uint32_t count = 0;
    check(api_.vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    if (count) check(api_.vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "vkEnumeratePhysicalDevices");
    devices.resize(count);
    return devices;
}

bool PhysicalDevice::subgroup_arithmetic() const {
    return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
           (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BASIC_BIT) &&
           (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT) && subgroup.subgroupSize > 0;
}

PhysicalDevice describe_device(const Instance& instance, VkPhysicalDevice device, int index) {
    const InstanceApi& api = instance.api();
    PhysicalDevice d;
    d.handle = device;
    api.vkGetPhysicalDeviceProperties(device, &d.properties);
    api.vkGetPhysicalDeviceMemoryProperties(device, &d.memory);
    VkPhysicalDeviceDriverProperties driver_props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    if (d.properties.apiVersion >= VK_API_VERSION_1_1) {
        d.subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
        // Driver name and version text are core in 1.2; older devices get the numeric version only.
        if (d.properties.apiVersion >= VK_API_VERSION_1_2) d.subgroup.pNext = &driver_props;
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        p2.pNext = &d.subgroup;
        api.vkGetPhysicalDeviceProperties2(device, &p2);
        d.subgroup.pNext = nullptr;
    } else {
        d.unusable = "supports only Vulkan " + version_text(d.properties.apiVersion) + " (1.1 needed)";
    }
    std::uint32_t families = 0;
    api.vkGetPhysicalDeviceQueueFamilyProperties(device, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    api.vkGetPhysicalDeviceQueueFamilyProperties(device, &families, props.data());
    for (std::uint32_t i = 0; i < families && d.compute_family < 0; ++i)
        if (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            d.compute_family = static_cast<int>(i);
            d.timestamp_bits = props[i].timestampValidBits;
        }
    if (d.compute_family < 0 && d.unusable.empty()) d.unusable = "has no queue family with compute support";

    VkDeviceSize device_local = 0;
    for (std::uint32_t i = 0; i < d.memory.memoryHeapCount; ++i)
        if (d.memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) device_local += d.memory.memoryHeaps[i].size;

    d.info.name = "vulkan:" + std::to_string(index);
    d.info.family = "vulkan";
    d.info.device = d.properties.deviceName;
    d.info.type = type_name(d.properties.deviceType);
    std::ostringstream driver;
    if (driver_props.driverName[0])
        driver << driver_props.driverName << " " << driver_props.driverInfo << ", ";
    driver << "Vulkan " << version_text(d.properties.apiVersion) << ", driver version 0x" << std::hex
           << d.properties.driverVersion << ", vendor 0x" << d.properties.vendorID;
    d.info.driver = driver.str();
    std::ostringstream details;
    details << "subgroup size " << d.subgroup.subgroupSize
            << (d.subgroup_arithmetic() ? " (arithmetic in compute)" : " (no compute subgroup arithmetic)")
            << ", max work-group " << d.properties.limits.maxComputeWorkGroupInvocations << ", device-local memory "
            << (device_local >> 20) << " MiB, max storage buffer " << (d.properties.limits.maxStorageBufferRange >> 20)
            << " MiB, timestamps " << (d.timestamp_bits ? "yes" : "no");
    if (!d.unusable.empty()) details << "; NOT USABLE: " << d.unusable;
    d.info.details = details.str();
    return d;
}

}  // namespace trn::vk
