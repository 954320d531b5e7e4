// Backends under test; see devices.hpp.
#include "devices.hpp"

#include <map>
#include <memory>

#include "backend_env.hpp"  // the TRN_* variables -> BackendOptions, as the CLI reads them
#include "trn/registry.hpp"

namespace trn::bench {

const std::vector<DeviceEntry>& bench_devices() {
    static const std::vector<DeviceEntry> devices = [] {
        std::vector<DeviceEntry> out;
        for (const FamilyStatus& s : default_registry().status(test::backend_options_from_environment()))
            for (const DeviceInfo& d : s.devices) out.push_back({d.name, d.family, d.type, d.device, d.details});
        return out;
    }();
    return devices;
}

Backend& backend_for(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Backend>> backends;
    auto& slot = backends[name];
    if (!slot) slot = default_registry().create(name, test::backend_options_from_environment());
    return *slot;
}

bool has_device_clock(const std::string& family) { return family == "opencl" || family == "vulkan" || family == "cuda"; }

}  // namespace trn::bench
