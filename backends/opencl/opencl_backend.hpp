#pragma once
#include <memory>

#include "cl_devices.hpp"
#include "trn/backend.hpp"
#include "trn/backend_options.hpp"

namespace trn::opencl {

// A backend on one OpenCL device: builds (or loads from the cache) its programs at creation and
// throws trn::Error with the build log when the device cannot compile them (or naming the option
// when `options` is out of range).
std::unique_ptr<Backend> make_opencl_backend(const DeviceRef& device, int index, const BackendOptions::OpenCl& options);

}  // namespace trn::opencl
