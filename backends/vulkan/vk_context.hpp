#pragma once
// One logical device with its compute queue: what every buffer, pipeline and submission of a
// Vulkan backend hangs off. Owns the instance it was created from.
#include <algorithm>
#include <memory>
#include <string>

#include "vk_instance.hpp"

namespace trn::vk {

class Context {
public:
    // Creates device `index` of the instance's physical devices; throws trn::Error naming the reason
    // (out of range, no compute queue, Vulkan < 1.1, vkCreateDevice failure).
    // force_staging: use staging buffers even where device memory is host-visible (to test that path).
    Context(std::unique_ptr<Instance> instance, int index, bool force_staging = false);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const InstanceApi& api() const { return instance_->api(); }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    std::uint32_t queue_family() const { return static_cast<std::uint32_t>(physical_.compute_family); }
    const PhysicalDevice& physical() const { return physical_; }
    const VkPhysicalDeviceLimits& limits() const { return physical_.properties.limits; }
    // The widest one-dimensional work-group a pipeline may ask for, and the subgroup width (>= 1):
    // what both the scoring and the Sobel shapes start from.
    std::uint32_t max_linear_group() const {
        return std::min(limits().maxComputeWorkGroupInvocations, limits().maxComputeWorkGroupSize[0]);
    }
    std::uint32_t subgroup_lanes() const { return std::max<std::uint32_t>(physical_.subgroup.subgroupSize, 1); }

    // Host-visible device-local memory is used directly (lavapipe, integrated GPUs); otherwise data
    // goes through host-visible staging buffers and copy commands. BackendOptions.vulkan.force_staging
    // forces the staging path (to test it on a unified-memory device).
    bool unified_memory() const { return unified_; }

    // Index of a memory type allowed by type_bits with all `required` flags, preferring `preferred`.
    // Throws trn::Error naming `what` when none fits.
    std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred,
                              const char* what) const;

    // Throws trn::Error quoting every validation message recorded since the last call (naming `call`).
    void throw_on_validation_messages(const char* call);

private:
    std::unique_ptr<Instance> instance_;
    PhysicalDevice physical_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    bool unified_ = false;
};

}  // namespace trn::vk
