#pragma once
// A Vulkan instance, optionally with the Khronos validation layer and a debug-utils messenger
// that records every warning and error so the backend can turn them into trn::Error.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "trn/backend.hpp"
#include "vk_api.hpp"

namespace trn::vk {

// Messages from the validation layer / loader, collected until someone takes them.
class MessageLog {
public:
    void add(std::string message);
    std::vector<std::string> take();

private:
    std::mutex mutex_;
    std::vector<std::string> messages_;
};

class Instance {
public:
    // validation: enable VK_LAYER_KHRONOS_validation + messenger (throws trn::Error when the layer
    // or VK_EXT_debug_utils is not installed).
    explicit Instance(bool validation);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    VkInstance handle() const { return instance_; }
    const InstanceApi& api() const { return api_; }
    bool validation() const { return messenger_ != VK_NULL_HANDLE; }
    MessageLog& messages() { return *log_; }
    std::vector<VkPhysicalDevice> physical_devices() const;

private:
    std::unique_ptr<MessageLog> log_ = std::make_unique<MessageLog>();
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    InstanceApi api_;
};

// What trnkit needs to know about one physical device.
struct PhysicalDevice {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceSubgroupProperties subgroup{};
    VkPhysicalDeviceMemoryProperties memory{};
    int compute_family = -1;         // queue family with compute, -1 when none
    std::uint32_t timestamp_bits = 0;  // of that family; 0: no timestamps
    std::string unusable;            // non-empty: why trnkit cannot use this device
    DeviceInfo info;
    bool subgroup_arithmetic() const;
};

PhysicalDevice describe_device(const Instance& instance, VkPhysicalDevice device, int index);

}  // namespace trn::vk
