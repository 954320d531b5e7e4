// Logical device creation and memory-type choice; see vk_context.hpp.
#include "vk_context.hpp"

#include <cstdlib>
#include <cstring>

namespace trn::vk {

Context::Context(std::unique_ptr<Instance> instance, int index, bool force_staging) : instance_(std::move(instance)) {
    const std::vector<VkPhysicalDevice> devices = instance_->physical_devices();
    if (index < 0 || index >= static_cast<int>(devices.size()))
        throw Error("vulkan: device index " + std::to_string(index) + " out of range (" + std::to_string(devices.size()) +
                    " device(s))");
    physical_ = describe_device(*instance_, devices[index], index);
    if (!physical_.unusable.empty())
        throw Error("vulkan: device " + std::to_string(index) + " (" + physical_.info.device + ") " + physical_.unusable);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family();
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    check(api().vkCreateDevice(physical_.handle, &info, nullptr, &device_), "vkCreateDevice");
    api().vkGetDeviceQueue(device_, queue_family(), 0, &queue_);

    const VkPhysicalDeviceType type = physical_.properties.deviceType;
    bool shared_type = false;
    const VkMemoryPropertyFlags both = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (std::uint32_t i = 0; i < physical_.memory.memoryTypeCount; ++i)
        if ((physical_.memory.memoryTypes[i].propertyFlags & both) == both) shared_type = true;
    unified_ = shared_type && (type == VK_PHYSICAL_DEVICE_TYPE_CPU || type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) &&
               !force_staging;
}

Context::~Context() {
    if (device_) {
        api().vkDeviceWaitIdle(device_);
        api().vkDestroyDevice(device_, nullptr);
    }
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                   VkMemoryPropertyFlags preferred, const char* what) const {
    const VkPhysicalDeviceMemoryProperties& m = physical_.memory;
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (std::uint32_t i = 0; i < m.memoryTypeCount; ++i)
            if ((type_bits & (1u << i)) && (m.memoryTypes[i].propertyFlags & want) == want) return i;
    throw Error(std::string("vulkan: no memory type for ") + what + " on " + physical_.info.device +
                " has the required properties (flags 0x" + std::to_string(required) + ")");
}

void Context::throw_on_validation_messages(const char* call) {
    const std::vector<std::string> messages = instance_->messages().take();
    if (messages.empty()) return;
    std::string text = std::string("vulkan: ") + std::to_string(messages.size()) + " validation message(s) during or before " +
                       call + ":";
    for (const std::string& m : messages) text += "\n  " + m;
    throw Error(text);
}

}  // namespace trn::vk
