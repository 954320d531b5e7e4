#pragma once
// NVIDIA GPU power through NVML, loaded at run time with dlopen (no build dependency; a machine
// without the driver gets a clear error, not a link failure). Two readings:
//  - board power, nvmlDeviceGetPowerUsage (mW) -> instant watts;
//  - the total energy counter, nvmlDeviceGetTotalEnergyConsumption (mJ since the driver loaded,
//    Volta and newer) -> interval-mean watts between polls, which sees every joule however short
//    the frame (newer GPUs average the power reading over up to a second).
// "nvml:INDEX" takes the counter when the GPU has one, else board power; ":power"/":energy" choose.
#include <memory>
#include <string>
#include <vector>

#include "trn/energy/power_sampler.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct NvmlSpec {
    unsigned index = 0;
    std::string reading;  // "power", "energy" or "" (energy where supported)
};
// "nvml", "nvml:1", "nvml:0:energy"; throws trn::Error naming the spec.
NvmlSpec parse_nvml_spec(const std::string& spec);

// "nvml:0 NAME (power, energy counter)" per device of the library at `library`.
std::vector<std::string> list_nvml_devices(const std::string& library);

class NvmlSampler final : public PowerSampler {
public:
    // Loads `library`, initialises NVML and opens the device; throws trn::Error naming nvml, the
    // library and the failing call (with nvmlErrorString) when any step fails.
    NvmlSampler(const NvmlSpec& spec, const std::string& library);
    ~NvmlSampler() override;
    NvmlSampler(const NvmlSampler&) = delete;
    NvmlSampler& operator=(const NvmlSampler&) = delete;
    std::string describe() const override;
    void poll(double t_s) override;
    PowerTrace trace() const override { return trace_; }
    bool energy_counter() const { return use_energy_; }

    struct Api;  // resolved NVML entry points (nvml_sampler.cpp)

private:
    std::shared_ptr<Api> api_;
    void* device_ = nullptr;
    unsigned index_ = 0;
    std::string name_, library_;
    bool use_energy_ = false, have_counter_ = false;
    unsigned long long last_mj_ = 0;
    double last_t_ = 0;
    PowerTrace trace_;
};

}  // namespace trn::energy
TRN_API_END
