#pragma once
#include "trn/registry.hpp"

namespace trn {
// The OpenCL family: every device of every OpenCL platform as "opencl:<n>"; the device for a
// bare "opencl" comes from BackendOptions.default_device["opencl"] (an index or a name substring).
BackendFamily opencl_family();
}  // namespace trn
