// Command recording, submission and timestamp reading; see vk_recorder.hpp.
#include "vk_recorder.hpp"

namespace trn::vk {

Recorder::Recorder(Context& context) : context_(context) {
    const InstanceApi& api = context.api();
    const VkDevice dev = context.device();
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    check(api.vkCreateCommandPool(dev, &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    check(api.vkAllocateCommandBuffers(dev, &alloc, &cmd_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(api.vkCreateFence(dev, &fence_info, nullptr, &fence_), "vkCreateFence");
    timestamps_ = context.physical().timestamp_bits > 0 && context.limits().timestampPeriod > 0;
    if (timestamps_) {
        VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        q.queryType = VK_QUERY_TYPE_TIMESTAMP;
        q.queryCount = kSlots;
        check(api.vkCreateQueryPool(dev, &q, nullptr, &queries_), "vkCreateQueryPool");
    }
}

Recorder::~Recorder() {
    const InstanceApi& api = context_.api();
    const VkDevice dev = context_.device();
    if (queries_) api.vkDestroyQueryPool(dev, queries_, nullptr);
    api.vkDestroyFence(dev, fence_, nullptr);
    api.vkDestroyCommandPool(dev, pool_, nullptr);
}

VkCommandBuffer Recorder::begin() {
    const InstanceApi& api = context_.api();
    check(api.vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(api.vkBeginCommandBuffer(cmd_, &info), "vkBeginCommandBuffer");
    if (timestamps_) api.vkCmdResetQueryPool(cmd_, queries_, 0, kSlots);
    marked_.fill(false);
    return cmd_;
}

void Recorder::mark(std::uint32_t slot) {
    if (!timestamps_) return;
    context_.api().vkCmdWriteTimestamp(cmd_, slot == 0 ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                                       queries_, slot);
    marked_[slot] = true;
}

void Recorder::barrier(VkPipelineStageFlags src_stage, VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                       VkAccessFlags dst_access) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    context_.api().vkCmdPipelineBarrier(cmd_, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void Recorder::submit_and_wait(const char* what) {
    const InstanceApi& api = context_.api();
    check(api.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    check(api.vkResetFences(context_.device(), 1, &fence_), "vkResetFences");
    check(api.vkQueueSubmit(context_.queue(), 1, &submit, fence_), what);
    check(api.vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), what);
    ticks_.fill(0);
    if (!timestamps_) return;
    for (std::uint32_t s = 0; s < kSlots; ++s) {
        if (!marked_[s]) continue;
        check(api.vkGetQueryPoolResults(context_.device(), queries_, s, 1, sizeof(std::uint64_t), &ticks_[s],
                                        sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults");
    }
    const std::uint32_t bits = context_.physical().timestamp_bits;
    if (bits < 64)
        for (std::uint64_t& t : ticks_) t &= (std::uint64_t(1) << bits) - 1;
}

double Recorder::elapsed_ms(std::uint32_t from, std::uint32_t to) const {
    if (!timestamps_ || !marked_[from] || !marked_[to] || ticks_[to] < ticks_[from]) return 0.0;
    return double(ticks_[to] - ticks_[from]) * context_.limits().timestampPeriod * 1e-6;
}

}  // namespace trn::vk
