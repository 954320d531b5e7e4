// Kernels, specialized pipelines and the on-disk pipeline cache; see vk_pipeline.hpp.
#include "vk_pipeline.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

namespace trn::vk {
namespace {

std::string cache_file_name(const VkPhysicalDeviceProperties& p) {
    std::ostringstream name;
    name << "vulkan-pipelines-" << std::hex << p.vendorID << "-" << p.deviceID << "-";
    for (std::uint8_t b : p.pipelineCacheUUID) name << (b >> 4) << (b & 15);
    name << ".bin";
    return name.str();
}

}  // namespace

PipelineCache::PipelineCache(Context& context, const std::string& folder) : context_(context) {
    if (!folder.empty()) path_ = folder + "/" + cache_file_name(context.physical().properties);
    std::vector<char> data;
    if (!path_.empty()) {
        std::ifstream in(path_, std::ios::binary);
        if (in) data.assign(std::istreambuf_iterator<char>(in), {});
    }
    // The driver checks the header (vendor, device, UUID) and ignores data that is not its own.
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = data.size();
    info.pInitialData = data.empty() ? nullptr : data.data();
    if (context.api().vkCreatePipelineCache(context.device(), &info, nullptr, &cache_) != VK_SUCCESS) {
        info.initialDataSize = 0, info.pInitialData = nullptr;  // unreadable old data: start empty
        check(context.api().vkCreatePipelineCache(context.device(), &info, nullptr, &cache_), "vkCreatePipelineCache");
    }
}

PipelineCache::~PipelineCache() {
    const InstanceApi& api = context_.api();
    if (!path_.empty()) {
        std::size_t size = 0;
        if (api.vkGetPipelineCacheData(context_.device(), cache_, &size, nullptr) == VK_SUCCESS && size > 0) {
            std::vector<char> data(size);
            if (api.vkGetPipelineCacheData(context_.device(), cache_, &size, data.data()) == VK_SUCCESS) {
                std::error_code ec;
                std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), ec);
                // Written next to the target and renamed, so concurrent processes never see half a file.
                const std::string tmp = path_ + ".tmp" + std::to_string(::getpid());
                {
                    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
                    out.write(data.data(), static_cast<std::streamsize>(size));
                }
                std::filesystem::rename(tmp, path_, ec);
                if (ec) std::filesystem::remove(tmp, ec);
            }
        }
    }
    api.vkDestroyPipelineCache(context_.device(), cache_, nullptr);
}

namespace {
VkDescriptorType descriptor_type(Binding::Kind kind) {
    return kind == Binding::Kind::StorageBuffer ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
}
}  // namespace

Kernel::Kernel(Context& context, PipelineCache& cache, std::span<const std::uint32_t> spirv, std::string name,
               std::vector<Binding> bindings, std::uint32_t push_constant_bytes)
    : context_(context), cache_(cache), name_(std::move(name)), bindings_(std::move(bindings)),
      push_bytes_(push_constant_bytes) {
    const InstanceApi& api = context.api();
    const VkDevice dev = context.device();
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size_bytes();
    module_info.pCode = spirv.data();
    check(api.vkCreateShaderModule(dev, &module_info, nullptr, &module_), "vkCreateShaderModule");

    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    std::uint32_t storage = 0, texel = 0;
    for (std::uint32_t i = 0; i < bindings_.size(); ++i) {
        layout_bindings.push_back({i, descriptor_type(bindings_[i].kind), bindings_[i].count, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        (bindings_[i].kind == Binding::Kind::StorageBuffer ? storage : texel) += bindings_[i].count;
    }
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = static_cast<std::uint32_t>(layout_bindings.size());
    set_info.pBindings = layout_bindings.data();
    check(api.vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");

    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    layout_info.pushConstantRangeCount = push_bytes_ ? 1 : 0;
    layout_info.pPushConstantRanges = &push;
    check(api.vkCreatePipelineLayout(dev, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");

    std::vector<VkDescriptorPoolSize> pool_sizes;
    if (storage) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage});
    if (texel) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, texel});
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = static_cast<std::uint32_t>(pool_sizes.size());
    pool_info.pPoolSizes = pool_sizes.data();
    check(api.vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout_;
    check(api.vkAllocateDescriptorSets(dev, &alloc, &set_), "vkAllocateDescriptorSets");

    // bind()'s write list, with room for every resource, so that binding allocates nothing.
    buffer_infos_.assign(storage, VkDescriptorBufferInfo{VK_NULL_HANDLE, 0, VK_WHOLE_SIZE});
    texel_views_.assign(texel, VK_NULL_HANDLE);
    std::uint32_t first_buffer = 0, first_view = 0;
    for (std::uint32_t i = 0; i < bindings_.size(); ++i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set_;
        w.dstBinding = i;
        w.descriptorCount = bindings_[i].count;
        w.descriptorType = descriptor_type(bindings_[i].kind);
        if (bindings_[i].kind == Binding::Kind::StorageBuffer) {
            w.pBufferInfo = buffer_infos_.data() + first_buffer;
            first_buffer += bindings_[i].count;
        } else {
            w.pTexelBufferView = texel_views_.data() + first_view;
            first_view += bindings_[i].count;
        }
        writes_.push_back(w);
    }
}

Kernel::~Kernel() {
    const InstanceApi& api = context_.api();
    const VkDevice dev = context_.device();
    for (const Specialized& s : pipelines_) api.vkDestroyPipeline(dev, s.pipeline, nullptr);
    api.vkDestroyDescriptorPool(dev, pool_, nullptr);
    api.vkDestroyPipelineLayout(dev, layout_, nullptr);
    api.vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
    api.vkDestroyShaderModule(dev, module_, nullptr);
}

VkPipeline Kernel::pipeline(std::span<const std::uint32_t> spec) {
    for (const Specialized& s : pipelines_)
        if (std::ranges::equal(s.spec, spec)) return s.pipeline;
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < spec.size(); ++i)
        entries.push_back({i, static_cast<std::uint32_t>(i * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
    VkSpecializationInfo spec_info{static_cast<std::uint32_t>(entries.size()), entries.data(),
                                   spec.size() * sizeof(std::uint32_t), spec.data()};
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module_;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = &spec_info;
    info.layout = layout_;
    VkPipeline p = VK_NULL_HANDLE;
    const VkResult r = context_.api().vkCreateComputePipelines(context_.device(), cache_.handle(), 1, &info, nullptr, &p);
    if (r != VK_SUCCESS) {
        // Vulkan has no build log; the validation layer's messages (when enabled) are the closest thing.
        std::string constants;
        for (std::uint32_t v : spec) constants += (constants.empty() ? "" : ", ") + std::to_string(v);
        std::string log;
        try {
            context_.throw_on_validation_messages("vkCreateComputePipelines");
        } catch (const Error& e) {
            log = std::string("\n") + e.what();
        }
        throw Error("vulkan: compiling kernel " + name_ + " (specialization constants " + constants + ") on " +
                    context_.physical().info.device + " failed: " + result_name(r) +
                    (log.empty() ? "; run with TRN_VULKAN_VALIDATION=1 for the validation layer's report" : log));
    }
    pipelines_.push_back({std::vector<std::uint32_t>(spec.begin(), spec.end()), p});
    return p;
}

void Kernel::bind(std::span<const VkBuffer> buffers, std::span<const VkBufferView> views) {
    if (buffers.size() != buffer_infos_.size() || views.size() != texel_views_.size())
        throw Error("vulkan: kernel " + name_ + " binds " + std::to_string(buffer_infos_.size()) + " buffers and " +
                    std::to_string(texel_views_.size()) + " texel views, got " + std::to_string(buffers.size()) + " and " +
                    std::to_string(views.size()));
    for (std::size_t k = 0; k < buffers.size(); ++k) buffer_infos_[k].buffer = buffers[k];
    std::copy(views.begin(), views.end(), texel_views_.begin());
    context_.api().vkUpdateDescriptorSets(context_.device(), static_cast<std::uint32_t>(writes_.size()), writes_.data(), 0, nullptr);
}

void Kernel::record_dispatch(VkCommandBuffer cmd, VkPipeline pipeline, const void* push, std::uint32_t gx, std::uint32_t gy) {
    const InstanceApi& api = context_.api();
    api.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    api.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    if (push_bytes_) api.vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
    api.vkCmdDispatch(cmd, gx, gy, 1);
}

}  // namespace trn::vk
