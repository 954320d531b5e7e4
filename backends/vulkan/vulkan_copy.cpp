// The Vulkan backend's memory-bandwidth probe: vkCmdCopyBuffer between two device-local buffers,
// each copy between two timestamp queries (the device's clock), after one untimed warm-up copy.
#include <vector>

#include "vulkan_backend_impl.hpp"

namespace trn::vk {

CopyBandwidth VulkanBackend::probe_copy_bandwidth(std::size_t bytes, int repetitions) {
    if (!recorder_->has_timestamps())
        throw Error("measure_copy_bandwidth: " + info_.name + " (" + info_.device + ") has no timestamp queries on its compute queue");
    Buffer src(*context_, Buffer::Place::Device, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "copy source");
    Buffer dst(*context_, Buffer::Place::Device, VK_BUFFER_USAGE_TRANSFER_DST_BIT, "copy destination");
    src.ensure(bytes);
    dst.ensure(bytes);
    const VkBufferCopy region{0, 0, bytes};
    std::vector<double> seconds;
    for (int i = 0; i <= repetitions; ++i) {
        VkCommandBuffer cmd = recorder_->begin();
        recorder_->mark(0);
        context_->api().vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
        recorder_->mark(1);
        recorder_->submit_and_wait("measure_copy_bandwidth (vkCmdCopyBuffer)");
        if (i > 0) seconds.push_back(recorder_->elapsed_ms(0, 1) * 1e-3);
    }
    return copy_bandwidth_from(bytes, std::move(seconds), "vkCmdCopyBuffer, timestamp queries");
}

}  // namespace trn::vk
