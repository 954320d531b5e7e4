#pragma once
#include <memory>

#include "cl_devices.hpp"
#include "trn/backend.hpp"

namespace trn::opencl {

// A backend on one OpenCL device: builds (or loads from the cache) its programs at creation and
// throws trn::Error with the build log when the device cannot compile them.
std::unique_ptr<Backend> make_opencl_backend(const DeviceRef& device, int index);

}  // namespace trn::opencl
