#pragma once
// One reusable command buffer with a fence and a timestamp query pool: record, submit, wait, and
// read the device's own clock for the phases in between. Calls are synchronous, so one of each is
// enough and nothing is allocated per call.
#include <array>
#include <cstdint>

#include "vk_context.hpp"

namespace trn::vk {

class Recorder {
public:
    static constexpr std::uint32_t kSlots = 4;  // start, uploaded, executed, downloaded
    explicit Recorder(Context& context);
    ~Recorder();
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    VkCommandBuffer begin();
    // Timestamp `slot` once every earlier command has finished (no-op without timestamp support).
    void mark(std::uint32_t slot);
    void barrier(VkPipelineStageFlags src_stage, VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                 VkAccessFlags dst_access);
    // Ends, submits and waits; `what` names the call in error messages.
    void submit_and_wait(const char* what);
    bool has_timestamps() const { return timestamps_; }
    // Milliseconds between two marked slots of the last submission (device clock).
    double elapsed_ms(std::uint32_t from, std::uint32_t to) const;

private:
    Context& context_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    bool timestamps_ = false;
    std::array<std::uint64_t, kSlots> ticks_{};
    std::array<bool, kSlots> marked_{};
};

}  // namespace trn::vk
