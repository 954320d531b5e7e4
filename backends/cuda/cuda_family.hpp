#pragma once
// The CUDA family: every device the NVIDIA driver reports, as cuda:<n>; the device for a bare
// "cuda" comes from BackendOptions.default_device["cuda"]. No cuda.h here: the registry includes it.
#include "trn/registry.hpp"

namespace trn {
BackendFamily cuda_family();
}  // namespace trn
