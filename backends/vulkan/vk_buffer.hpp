#pragma once
// Storage buffers: one VkBuffer with its own memory, and a Mirror that pairs a device buffer with a
// host-visible staging twin on devices that distinguish them (one mapped buffer on unified memory).
// Both only grow, so steady-state calls allocate nothing.
#include <cstddef>

#include "vk_context.hpp"

namespace trn::vk {

class Buffer {
public:
    enum class Place { Device, Host };  // Host: host-visible, coherent and persistently mapped
    Buffer(Context& context, Place place, VkBufferUsageFlags usage, const char* what);
    ~Buffer();
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    // Reallocates (contents lost) when smaller than `bytes`.
    void ensure(VkDeviceSize bytes);
    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }

private:
    void release();
    Context& context_;
    Place place_;
    VkBufferUsageFlags usage_;
    const char* what_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

class Mirror {
public:
    // shader_usage: how shaders see the device buffer (transfer bits are always added).
    Mirror(Context& context, const char* what, VkBufferUsageFlags shader_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    void ensure(VkDeviceSize bytes);
    // Where the host writes input / reads results.
    void* host() const { return staging_ ? staging_->mapped() : device_.mapped(); }
    VkBuffer device() const { return device_.handle(); }
    bool staged() const { return staging_ != nullptr; }
    // Records the staging -> device copy (nothing on unified memory).
    void record_upload(VkCommandBuffer cmd, VkDeviceSize bytes) const;
    // Records the device -> staging copy (nothing on unified memory).
    void record_download(VkCommandBuffer cmd, VkDeviceSize bytes) const;
    // Frees the staging twin (after a one-off upload such as a map).
    void drop_staging() { staging_.reset(); }

private:
    Context& context_;
    Buffer device_;
    std::unique_ptr<Buffer> staging_;
};

// A VkBufferView over the first `elements` texels of a buffer (for uniform texel buffers).
class TexelView {
public:
    TexelView(Context& context, VkBuffer buffer, VkFormat format, VkDeviceSize bytes);
    ~TexelView();
    TexelView(const TexelView&) = delete;
    TexelView& operator=(const TexelView&) = delete;
    VkBufferView handle() const { return view_; }

private:
    Context& context_;
    VkBufferView view_ = VK_NULL_HANDLE;
};

}  // namespace trn::vk
