#pragma once
#include <memory>

#include "trn/backend.hpp"
#include "trn/backend_options.hpp"

namespace trn::cuda {

// A backend on CUDA device `index` (cuDeviceGet order): loads the embedded kernels at creation and
// throws trn::BackendUnavailable when the device has no code in this build (e.g. sm_72 from a CUDA
// 13 toolkit), trn::Error with the driver's words when loading fails or `options` is out of range.
std::unique_ptr<Backend> make_cuda_backend(int index, const BackendOptions::Cuda& options);

}  // namespace trn::cuda
