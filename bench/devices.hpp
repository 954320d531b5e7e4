#pragma once
// The backends under test, created once per device name from the registry and kept for the
// whole run (creation compiles kernels; that cost is measured by the setup benchmarks only).
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::bench {

struct DeviceEntry {
    std::string name;    // registry name: "cpu-ref", "cpu", "opencl:0", ...
    std::string family;  // "cpu-ref", "cpu", "opencl", "vulkan"
    std::string type;    // "cpu", "gpu", "other" (DeviceInfo::type)
    std::string device;  // e.g. "NVIDIA H200"
    std::string details;  // DeviceInfo::details (the cpu backend's: its threads and inner loop)
};

// Every device the registry lists in this build, in registry order.
const std::vector<DeviceEntry>& bench_devices();

// The shared backend for a device (created on first use).
Backend& backend_for(const std::string& name);

// True when the backend's PhaseTimes come from a device clock (OpenCL events, Vulkan timestamps,
// CUDA events) rather than the host's steady_clock around the call.
bool has_device_clock(const std::string& family);

}  // namespace trn::bench
