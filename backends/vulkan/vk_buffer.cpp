// Buffer allocation with clear out-of-memory errors; see vk_buffer.hpp.
#include "vk_buffer.hpp"

namespace trn::vk {

Buffer::Buffer(Context& context, Place place, VkBufferUsageFlags usage, const char* what)
    : context_(context), place_(place), usage_(usage), what_(what) {}

Buffer::~Buffer() { release(); }

void Buffer::release() {
    const InstanceApi& api = context_.api();
    if (mapped_) api.vkUnmapMemory(context_.device(), memory_);
    if (buffer_) api.vkDestroyBuffer(context_.device(), buffer_, nullptr);
    if (memory_) api.vkFreeMemory(context_.device(), memory_, nullptr);
    mapped_ = nullptr, buffer_ = VK_NULL_HANDLE, memory_ = VK_NULL_HANDLE, size_ = 0;
}

void Buffer::ensure(VkDeviceSize bytes) {
    if (bytes <= size_) return;
    release();
    const InstanceApi& api = context_.api();
    const VkDeviceSize limit = context_.limits().maxStorageBufferRange;
    if ((usage_ & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && bytes > limit)
        throw Error(std::string("vulkan: ") + what_ + " needs " + std::to_string(bytes) + " bytes, more than the device's " +
                    "maxStorageBufferRange of " + std::to_string(limit) + " bytes");
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = usage_;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(api.vkCreateBuffer(context_.device(), &info, nullptr, &buffer_), "vkCreateBuffer");
    VkMemoryRequirements req;
    api.vkGetBufferMemoryRequirements(context_.device(), buffer_, &req);
    const bool host = place_ == Place::Host;
    const VkMemoryPropertyFlags required =
        host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    // Host buffers on unified memory are the device buffers too: prefer device-local ones.
    const VkMemoryPropertyFlags preferred = host ? (context_.unified_memory() ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                                                             : VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
                                                 : 0;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context_.memory_type(req.memoryTypeBits, required, preferred, what_);
    const VkResult r = api.vkAllocateMemory(context_.device(), &alloc, nullptr, &memory_);
    if (r != VK_SUCCESS) {
        api.vkDestroyBuffer(context_.device(), buffer_, nullptr);
        buffer_ = VK_NULL_HANDLE;
        check(r, (std::string("vkAllocateMemory(") + std::to_string(req.size) + " bytes for " + what_ + ")").c_str());
    }
    check(api.vkBindBufferMemory(context_.device(), buffer_, memory_, 0), "vkBindBufferMemory");
    if (host) check(api.vkMapMemory(context_.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    size_ = bytes;
}

namespace {
constexpr VkBufferUsageFlags kTransfers = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr VkBufferUsageFlags kStaging = kTransfers;
}  // namespace

Mirror::Mirror(Context& context, const char* what, VkBufferUsageFlags shader_usage)
    : context_(context),
      device_(context, context.unified_memory() ? Buffer::Place::Host : Buffer::Place::Device, kTransfers | shader_usage, what) {
    if (!context.unified_memory()) staging_ = std::make_unique<Buffer>(context, Buffer::Place::Host, kStaging, what);
}

void Mirror::ensure(VkDeviceSize bytes) {
    device_.ensure(bytes);
    if (staging_) staging_->ensure(bytes);
}

void Mirror::record_upload(VkCommandBuffer cmd, VkDeviceSize bytes) const {
    if (!staging_ || bytes == 0) return;
    const VkBufferCopy region{0, 0, bytes};
    context_.api().vkCmdCopyBuffer(cmd, staging_->handle(), device_.handle(), 1, &region);
}

void Mirror::record_download(VkCommandBuffer cmd, VkDeviceSize bytes) const {
    if (!staging_ || bytes == 0) return;
    const VkBufferCopy region{0, 0, bytes};
    context_.api().vkCmdCopyBuffer(cmd, device_.handle(), staging_->handle(), 1, &region);
}

TexelView::TexelView(Context& context, VkBuffer buffer, VkFormat format, VkDeviceSize bytes) : context_(context) {
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = buffer;
    info.format = format;
    info.offset = 0;
    info.range = bytes;
    check(context.api().vkCreateBufferView(context.device(), &info, nullptr, &view_), "vkCreateBufferView");
}

TexelView::~TexelView() { context_.api().vkDestroyBufferView(context_.device(), view_, nullptr); }

}  // namespace trn::vk
