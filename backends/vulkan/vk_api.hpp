#pragma once
// The Vulkan C API, loaded at run time from libvulkan.so.1 (dlopen) so that a machine without the
// Vulkan loader still runs trnkit and `trnkit devices` says what is missing instead of the
// program failing to start. Also: VkResult -> text and the check() helper every call goes through.
#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <string>

namespace trn::vk {

// Functions resolved through vkGetInstanceProcAddr for one instance.
#define TRN_VK_INSTANCE_FUNCTIONS(X)                                                                        \
    X(vkDestroyInstance) X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties)                    \
    X(vkGetPhysicalDeviceProperties2) X(vkGetPhysicalDeviceFeatures) X(vkGetPhysicalDeviceQueueFamilyProperties) \
    X(vkGetPhysicalDeviceMemoryProperties) X(vkCreateDevice) X(vkCreateDebugUtilsMessengerEXT)              \
    X(vkDestroyDebugUtilsMessengerEXT) X(vkDestroyDevice) X(vkGetDeviceQueue) X(vkCreateBuffer)           \
    X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements) X(vkAllocateMemory) X(vkFreeMemory)                \
    X(vkBindBufferMemory) X(vkMapMemory) X(vkUnmapMemory) X(vkCreateShaderModule) X(vkDestroyShaderModule) \
    X(vkCreateDescriptorSetLayout) X(vkDestroyDescriptorSetLayout) X(vkCreatePipelineLayout)               \
    X(vkDestroyPipelineLayout) X(vkCreateComputePipelines) X(vkDestroyPipeline) X(vkCreatePipelineCache)   \
    X(vkDestroyPipelineCache) X(vkGetPipelineCacheData) X(vkCreateDescriptorPool) X(vkDestroyDescriptorPool) \
    X(vkAllocateDescriptorSets) X(vkUpdateDescriptorSets) X(vkCreateCommandPool) X(vkDestroyCommandPool)   \
    X(vkAllocateCommandBuffers) X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkResetCommandBuffer)      \
    X(vkCmdBindPipeline) X(vkCmdBindDescriptorSets) X(vkCmdPushConstants) X(vkCmdDispatch)                 \
    X(vkCmdCopyBuffer) X(vkCmdPipelineBarrier) X(vkCmdResetQueryPool) X(vkCmdWriteTimestamp)               \
    X(vkCreateQueryPool) X(vkDestroyQueryPool) X(vkGetQueryPoolResults) X(vkCreateFence) X(vkDestroyFence) \
    X(vkResetFences) X(vkWaitForFences) X(vkQueueSubmit) X(vkDeviceWaitIdle) X(vkCreateBufferView)           \
    X(vkDestroyBufferView)

struct InstanceApi {
#define TRN_VK_MEMBER(name) PFN_##name name = nullptr;
    TRN_VK_INSTANCE_FUNCTIONS(TRN_VK_MEMBER)
#undef TRN_VK_MEMBER
};

// Process-wide entry points from the loader; throws trn::BackendUnavailable when libvulkan.so.1
// cannot be loaded.
struct LoaderApi {
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
    PFN_vkCreateInstance vkCreateInstance = nullptr;
    PFN_vkEnumerateInstanceLayerProperties vkEnumerateInstanceLayerProperties = nullptr;
    PFN_vkEnumerateInstanceExtensionProperties vkEnumerateInstanceExtensionProperties = nullptr;
    PFN_vkEnumerateInstanceVersion vkEnumerateInstanceVersion = nullptr;  // null on a Vulkan 1.0 loader
};
const LoaderApi& loader();

// Resolves every function of TRN_VK_INSTANCE_FUNCTIONS for `instance` (debug-utils ones may stay null).
InstanceApi load_instance_api(VkInstance instance);

const char* result_name(VkResult r);

// Throws trn::Error "vulkan: <call> failed: VK_ERROR_... (<hint>)" unless r is VK_SUCCESS.
void check(VkResult r, const char* call);

}  // namespace trn::vk
