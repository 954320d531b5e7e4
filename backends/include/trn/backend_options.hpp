#pragma once
// Settings a backend is created with, passed by value to BackendRegistry::create. The library
// never reads the environment: the `trnkit` CLI builds these from its TRN_* variables
// (apps/trnkit/backend_env.cpp, listed in README.md), an embedding program sets them itself or from
// NAME=VALUE text (trn/backend_option_text.hpp).
// Defaults are the tuned values; each backend checks its own fields when it is created and throws
// trn::Error naming the field (e.g. "BackendOptions.vulkan.work_group = 48: ...").
#include <cstdint>
#include <map>
#include <string>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct BackendOptions {
    // Device used when a spec names only the family ("opencl"), keyed by family: an index or a name
    // text as after the colon ("1", "pocl"). Absent or empty: device 0.
    std::map<std::string, std::string> default_device;

    struct Cpu {
        int threads = 0;    // worker threads; 0: the hardware threads
        bool simd = true;   // false: the portable inner loop even where AVX2 (x86-64) or NEON (aarch64) is there
    } cpu;

    struct OpenCl {
        std::uint32_t work_group = 0;     // NCC work-group size, a power of two; 0: from device queries (ncc_work_shape.hpp)
        std::string program_cache_dir;    // folder for compiled program binaries; empty: no disk cache
    } opencl;

    struct Vulkan {
        std::uint32_t work_group = 0;           // scoring work-group, power of two in [1, 1024]; 0: from device queries
        std::uint32_t particles_per_group = 0;  // 1..16; 0: from device queries (ncc_work_shape.hpp)
        bool quad_maps = true;                  // false: maps stay one byte per pixel (tests that path)
        bool subgroups = true;                  // false: the shared-memory reduction even with subgroup arithmetic
        bool force_staging = false;             // true: staging buffers even with unified memory
        bool validation = false;                // Khronos validation layer; any message it reports throws
        std::string pipeline_cache_dir;         // folder for the pipeline cache file; empty: no disk cache
    } vulkan;

    struct Cuda {
        std::uint32_t work_group = 0;  // NCC threads per block, a power of two in [32, 1024]; 0: from device queries (ncc_work_shape.hpp)
    } cuda;
};

}  // namespace trn
TRN_API_END
