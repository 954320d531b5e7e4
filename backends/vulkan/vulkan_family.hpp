#pragma once
// The Vulkan backend family: every physical device the loader reports (lavapipe included) as
// vulkan:<n>; BackendOptions.default_device["vulkan"] picks one by index or name when only "vulkan" is asked for.
#include "trn/registry.hpp"

namespace trn {
BackendFamily vulkan_family();
}  // namespace trn
