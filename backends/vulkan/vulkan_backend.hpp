#pragma once
#include <memory>

#include "trn/backend.hpp"
#include "trn/backend_options.hpp"

namespace trn {
// The backend on Vulkan physical device `index` (enumeration order, as listed by vulkan_family()).
// With options.validation the Khronos validation layer is enabled and any message it reports
// makes the call during or after which it arrived throw trn::Error.
std::unique_ptr<Backend> make_vulkan_backend(int index, const BackendOptions::Vulkan& options);
}  // namespace trn
