#pragma once
// The explicit list of backends this build knows (no static-initialisation magic): each family
// says which devices it sees, or why it has none, and creates a backend for one of them.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "trn/backend.hpp"
#include "trn/backend_options.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct BackendFamily {
    std::string name;         // "cpu-ref", "cpu", "opencl", "vulkan"
    std::string description;  // one line for `trnkit devices`
    // Lists this family's devices. When it has none it returns an empty list and says why.
    std::function<std::vector<DeviceInfo>(const BackendOptions& options, std::string& why_none)> list_devices;
    // Creates a backend on device `index` of list_devices(), with the family's part of `options`.
    std::function<std::unique_ptr<Backend>(int index, const BackendOptions& options)> create;
};

// One candidate of "fastest", timed only when a caller asks (create_fastest with timings).
struct BackendTiming {
    std::string name;     // "opencl:0", "cpu", ...
    double score_ms = 0;  // one batch (a 160x120 template, 1000 particles), after a warm-up batch
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
    // `options` only changes what the details say (e.g. the OpenCL program cache in use).
    std::vector<FamilyStatus> status(const BackendOptions& options = {}) const;
    // Names of every usable device ("cpu-ref", "cpu", "opencl:0", ...).
    std::vector<std::string> available() const;

    // Creates a backend from a spec: "cpu", "opencl" (the device in
    // options.default_device["opencl"], else device 0), "opencl:1" (by index) or "opencl:pocl"
    // (first device whose device or driver name contains the text, case-insensitive), or
    // "fastest" (below). Throws BackendUnavailable, saying why, when it cannot: it never falls back
    // to another backend. Throws trn::Error naming the field when an option is out of range.
    std::unique_ptr<Backend> create(std::string_view spec, BackendOptions options = {}) const;

    // "fastest": a fixed preference order, so that two runs on one machine always pick the same
    // backend (a timing race could flip between near-equal devices): GPU devices (OpenCL, then
    // Vulkan, then other families such as CUDA, by name), then the optimised CPU backend, then any other device (e.g. PoCL or
    // lavapipe on the CPU), and cpu-ref (the slow oracle) only when it is the only one.
    // The device names in that order; pure, so the order is testable.
    static std::vector<std::string> preferred_order(const std::vector<DeviceInfo>& devices);
    // The first device in preferred_order() that can be created with `options`. Nothing is timed
    // unless `timings` is given: then every usable candidate is also created and scores one batch
    // after a warm-up (for a printout), a candidate that fails it is skipped, and the choice is
    // still the first usable one in preferred_order(), never the quickest of this run.
    std::unique_ptr<Backend> create_fastest(BackendOptions options = {}, std::vector<BackendTiming>* timings = nullptr) const;

private:
    std::vector<BackendFamily> families_;
};

// cpu-ref, cpu, opencl, vulkan and cuda; a family this build lacks is listed with the reason.
const BackendRegistry& default_registry();

}  // namespace trn
TRN_API_END
