#pragma once
// The trnkit CLI's TRN_* environment variables -> trn::BackendOptions (the library itself never
// reads the environment; it parses the values, trn/backend_option_text.hpp). The test and benchmark
// mains read the same variables through tests/common/backend_env.hpp.
//   TRN_OPENCL_DEVICE, TRN_VULKAN_DEVICE     device when only the family is named (index or name text)
//   TRN_CPU_THREADS=N                        worker threads of the cpu backend (default: hardware threads)
//   TRN_CPU_SIMD=off                         portable inner loop instead of AVX2 / NEON
//   TRN_OPENCL_WORK_GROUP=N                  NCC work-group size (power of two)
//   TRN_OPENCL_CACHE=0                       no program binary cache ($XDG_CACHE_HOME/trnkit/opencl,
//                                            else ~/.cache/trnkit/opencl)
//   TRN_VULKAN_WORKGROUP=N                   scoring work-group (power of two, 1..1024)
//   TRN_VULKAN_PARTICLES_PER_GROUP=N         particles per scoring work-group (1..16)
//   TRN_VULKAN_MAP_LAYOUT=bytes              maps one byte per pixel (no quad layout)
//   TRN_VULKAN_NO_SUBGROUPS=1                shared-memory reduction instead of subgroup arithmetic
//   TRN_VULKAN_FORCE_STAGING=1               staging buffers even with unified memory
//   TRN_VULKAN_VALIDATION=1                  Khronos validation layer; any message fails the call
//   TRN_VULKAN_PIPELINE_CACHE_DIR=DIR        pipeline cache folder ("" : none; default
//                                            $XDG_CACHE_HOME/trnkit, else ~/.cache/trnkit)
#include "trn/backend_options.hpp"

namespace trn::cli {

// Reads the variables above; a malformed value throws trn::Error naming the variable and value
// (the library's BackendOptionError names its option; this names the variable instead).
BackendOptions backend_options_from_environment();

}  // namespace trn::cli
