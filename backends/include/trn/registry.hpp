#pragma once
// The explicit list of backends this build knows (no static-initialisation magic): each family
// says which devices it sees, or why it has none, and creates a backend for one of them.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "trn/backend.hpp"

namespace trn {

struct BackendFamily {
    std::string name;         // "cpu-ref", "cpu", "opencl", "vulkan"
    std::string description;  // one line for `trnkit devices`
    // Lists this family's devices. When it has none it returns an empty list and says why.
    std::function<std::vector<DeviceInfo>(std::string& why_none)> list_devices;
    // Creates a backend on device `index` of list_devices().
    std::function<std::unique_ptr<Backend>(int index)> create;
    // Environment variable that picks the device when only the family is named ("" for none).
    std::string device_env;
};

struct FamilyStatus {
    std::string family;
    std::string description;
    std::vector<DeviceInfo> devices;
    std::string why_none;  // non-empty when devices is empty
};

class BackendRegistry {
public:
    void add(BackendFamily family);
    const std::vector<BackendFamily>& families() const { return families_; }

    // Every family with its devices or the reason it has none (enumerates devices; not cheap).
    std::vector<FamilyStatus> status() const;
    // Names of every usable device ("cpu-ref", "cpu", "opencl:0", ...).
    std::vector<std::string> available() const;

    // Creates a backend from a spec: "cpu", "opencl" (the device in $TRN_OPENCL_DEVICE, else
    // device 0), "opencl:1" (by index) or "opencl:pocl" (first device whose device or driver name
    // contains the text, case-insensitive). Throws BackendUnavailable, saying why, when it cannot: it never
    // falls back to another backend.
    std::unique_ptr<Backend> create(std::string_view spec) const;

private:
    std::vector<BackendFamily> families_;
};

// cpu-ref, cpu, and the OpenCL and Vulkan families when this build has them.
const BackendRegistry& default_registry();

}  // namespace trn
