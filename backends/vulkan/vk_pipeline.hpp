#pragma once
// Compute kernels: a SPIR-V module with its descriptor set layout (storage and uniform texel buffers), push
// constant block and one descriptor set, plus pipelines specialized per set of specialization
// constants (created on first use, kept for the kernel's life). A VkPipelineCache persisted on
// disk makes later runs skip the driver's shader compilation. Once a pipeline exists, pipeline(),
// bind() and record_dispatch() allocate nothing on the host (steady-state calls must not).
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "vk_context.hpp"

namespace trn::vk {

class PipelineCache {
public:
    // Loads the cache file for this device from `folder` when present (see path()); "" keeps the
    // cache in memory only.
    PipelineCache(Context& context, const std::string& folder);
    // Writes the cache back (atomically; a failure to write is ignored: it is only a cache).
    ~PipelineCache();
    VkPipelineCache handle() const { return cache_; }
    // BackendOptions.vulkan.pipeline_cache_dir (the CLI: $TRN_VULKAN_PIPELINE_CACHE_DIR, else
    // $XDG_CACHE_HOME/trnkit, else $HOME/.cache/trnkit) plus a file name made of the vendor, device
    // and pipeline-cache UUID. Empty: no persistence.
    const std::string& path() const { return path_; }

private:
    Context& context_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::string path_;
};

// Binding i of a kernel's descriptor set: `count` descriptors of one type.
struct Binding {
    enum class Kind { StorageBuffer, UniformTexelBuffer };
    Kind kind = Kind::StorageBuffer;
    std::uint32_t count = 1;
};

class Kernel {
public:
    Kernel(Context& context, PipelineCache& cache, std::span<const std::uint32_t> spirv, std::string name,
           std::vector<Binding> bindings, std::uint32_t push_constant_bytes);
    ~Kernel();
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    // The pipeline for specialization constants 0..n-1 = spec (all 32-bit).
    VkPipeline pipeline(std::span<const std::uint32_t> spec);
    VkPipeline pipeline(std::initializer_list<std::uint32_t> spec) { return pipeline(std::span(spec.begin(), spec.size())); }
    // Points every binding at its resources: `buffers` lists the whole buffers of the storage-buffer
    // bindings in binding order (count of each), `views` those of the texel-buffer bindings.
    void bind(std::span<const VkBuffer> buffers, std::span<const VkBufferView> views = {});
    void bind(std::initializer_list<VkBuffer> buffers) { bind(std::span(buffers.begin(), buffers.size())); }
    // Records bind pipeline + descriptor set + push constants + dispatch.
    void record_dispatch(VkCommandBuffer cmd, VkPipeline pipeline, const void* push, std::uint32_t gx, std::uint32_t gy = 1);

private:
    Context& context_;
    PipelineCache& cache_;
    std::string name_;
    std::vector<Binding> bindings_;
    std::uint32_t push_bytes_;
    VkShaderModule module_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    // bind()'s write list, sized once here so that binding allocates nothing.
    std::vector<VkDescriptorBufferInfo> buffer_infos_;
    std::vector<VkBufferView> texel_views_;
    std::vector<VkWriteDescriptorSet> writes_;
    // A kernel has a handful of specializations: a linear search needs no key built per lookup.
    struct Specialized {
        std::vector<std::uint32_t> spec;
        VkPipeline pipeline;
    };
    std::vector<Specialized> pipelines_;
};

}  // namespace trn::vk
