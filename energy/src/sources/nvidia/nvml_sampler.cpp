#include "trn/energy/nvml_sampler.hpp"

#include <dlfcn.h>

#include <cstring>

#include "text_input.hpp"
#include "trn/error.hpp"

namespace trn::energy {

// The NVML C API as the driver's libnvidia-ml.so.1 exports it (nvml.h): return codes are ints,
// 0 = NVML_SUCCESS; devices are opaque pointers.
struct NvmlSampler::Api {
    using Ret = int;
    void* lib = nullptr;
    std::string library;
    Ret (*init)() = nullptr;
    Ret (*shutdown)() = nullptr;
    const char* (*error_string)(Ret) = nullptr;
    Ret (*count)(unsigned*) = nullptr;
    Ret (*handle)(unsigned, void**) = nullptr;
    Ret (*name)(void*, char*, unsigned) = nullptr;
    Ret (*power)(void*, unsigned*) = nullptr;
    Ret (*energy)(void*, unsigned long long*) = nullptr;

    // Loads and initialises; throws naming the library and the step.
    explicit Api(const std::string& path) : library(path) {
        lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            const char* why = dlerror();
            throw Error("nvml: cannot load '" + path + "' (" + (why ? why : "dlopen failed") + "): no NVIDIA driver here, or give the library's path");
        }
        try {
            resolve(init, "nvmlInit_v2");
            resolve(shutdown, "nvmlShutdown");
            resolve(error_string, "nvmlErrorString");
            resolve(count, "nvmlDeviceGetCount_v2");
            resolve(handle, "nvmlDeviceGetHandleByIndex_v2");
            resolve(power, "nvmlDeviceGetPowerUsage");
            // Optional: older drivers lack these.
            name = reinterpret_cast<decltype(name)>(dlsym(lib, "nvmlDeviceGetName"));
            energy = reinterpret_cast<decltype(energy)>(dlsym(lib, "nvmlDeviceGetTotalEnergyConsumption"));
            check(init(), "nvmlInit_v2");
        } catch (...) {
            dlclose(lib);
            throw;
        }
    }
    ~Api() {
        shutdown();
        dlclose(lib);
    }
    Api(const Api&) = delete;
    Api& operator=(const Api&) = delete;

    template <class F>
    void resolve(F& f, const char* symbol) {
        f = reinterpret_cast<F>(dlsym(lib, symbol));
        if (!f) throw Error("nvml: '" + library + "' does not export " + symbol + " (not an NVML library?)");
    }
    std::string why(Ret r) const {
        const char* s = error_string ? error_string(r) : nullptr;
        return (s ? std::string(s) : std::string("error")) + ", code " + std::to_string(r);
    }
    void check(Ret r, const std::string& call) const {
        if (r != 0) throw Error("nvml: " + call + " failed (" + why(r) + ") in '" + library + "'");
    }
    unsigned devices() const {
        unsigned n = 0;
        check(count(&n), "nvmlDeviceGetCount_v2");
        return n;
    }
    std::string device_name(void* dev) const {
        char buf[96] = {};
        if (!name || name(dev, buf, sizeof buf) != 0) return "NVIDIA GPU";
        buf[sizeof buf - 1] = 0;
        return buf;
    }
    bool has_energy_counter(void* dev) const {
        unsigned long long mj = 0;
        return energy && energy(dev, &mj) == 0;
    }
};

NvmlSpec parse_nvml_spec(const std::string& spec) {
    const auto parts = text::split(spec, ':');
    NvmlSpec s;
    if (parts.empty() || parts[0] != "nvml" || parts.size() > 3) throw Error("source '" + spec + "': expected nvml[:INDEX[:power|:energy]]");
    if (parts.size() >= 2) {
        const auto n = text::to_number(parts[1]);
        if (!n || *n < 0 || *n > 1e6 || *n != static_cast<double>(static_cast<unsigned>(*n)))
            throw Error("source '" + spec + "': the GPU index must be a whole number >= 0");
        s.index = static_cast<unsigned>(*n);
    }
    if (parts.size() == 3) {
        s.reading = std::string(parts[2]);
        if (s.reading != "power" && s.reading != "energy") throw Error("source '" + spec + "': reading must be power or energy");
    }
    return s;
}

std::vector<std::string> list_nvml_devices(const std::string& library) {
    NvmlSampler::Api api(library);
    std::vector<std::string> out;
    const unsigned n = api.devices();
    for (unsigned i = 0; i < n; ++i) {
        void* dev = nullptr;
        api.check(api.handle(i, &dev), "nvmlDeviceGetHandleByIndex_v2(" + std::to_string(i) + ")");
        out.push_back("nvml:" + std::to_string(i) + " " + api.device_name(dev) + " (board power" +
                      (api.has_energy_counter(dev) ? ", energy counter)" : "; no energy counter)"));
    }
    return out;
}

NvmlSampler::NvmlSampler(const NvmlSpec& spec, const std::string& library) : api_(std::make_shared<Api>(library)), index_(spec.index), library_(library) {
    const unsigned n = api_->devices();
    if (spec.index >= n)
        throw Error("nvml:" + std::to_string(spec.index) + ": no such GPU ('" + library + "' reports " + std::to_string(n) + " device(s))");
    api_->check(api_->handle(spec.index, &device_), "nvmlDeviceGetHandleByIndex_v2(" + std::to_string(spec.index) + ")");
    name_ = api_->device_name(device_);
    const bool counter = api_->has_energy_counter(device_);
    if (spec.reading == "energy" && !counter)
        throw Error("nvml:" + std::to_string(spec.index) + ":energy: " + name_ + " has no total energy counter (" +
                    (api_->energy ? "nvmlDeviceGetTotalEnergyConsumption fails" : "'" + library + "' does not export nvmlDeviceGetTotalEnergyConsumption") +
                    "); use nvml:" + std::to_string(spec.index) + ":power");
    use_energy_ = spec.reading == "energy" || (spec.reading.empty() && counter);
    if (!use_energy_) {
        unsigned mw = 0;
        api_->check(api_->power(device_, &mw), "nvmlDeviceGetPowerUsage(" + name_ + ")");
    }
    trace_.source = "nvml:" + std::to_string(index_) + " " + name_;
    trace_.format = "trnkit";
    if (use_energy_) {
        trace_.kind = SampleKind::IntervalMean;
        trace_.quantity = "nvml total energy counter (mJ)";
    } else {
        trace_.kind = SampleKind::Instant;
        trace_.quantity = "nvml board power (mW)";
        trace_.resolution_w = 1e-3;
        trace_.notes.push_back("NVML board power: on many GPUs an average over up to 1 s, not an instant reading; prefer :energy where supported");
    }
}

NvmlSampler::~NvmlSampler() = default;

std::string NvmlSampler::describe() const {
    return "nvml:" + std::to_string(index_) + (use_energy_ ? ":energy" : ":power") + " (" + name_ + ", " + library_ + ")";
}

void NvmlSampler::poll(double t) {
    if ((have_counter_ || !trace_.t.empty()) && !(t > last_t_)) throw Error(describe() + ": poll times must increase");
    if (use_energy_) {
        unsigned long long mj = 0;
        api_->check(api_->energy(device_, &mj), "nvmlDeviceGetTotalEnergyConsumption(" + name_ + ")");
        if (!have_counter_) {
            have_counter_ = true, last_mj_ = mj, last_t_ = t;
            trace_.first_interval_start = t;
            return;
        }
        // A 64-bit millijoule counter does not wrap in a GPU's lifetime: a step back is a fault.
        if (mj < last_mj_) throw Error(describe() + ": total energy counter stepped back from " + std::to_string(last_mj_) + " to " + std::to_string(mj) + " mJ");
        trace_.t.push_back(t);
        trace_.w.push_back(static_cast<double>(mj - last_mj_) * 1e-3 / (t - last_t_));
        last_mj_ = mj, last_t_ = t;
        return;
    }
    unsigned mw = 0;
    api_->check(api_->power(device_, &mw), "nvmlDeviceGetPowerUsage(" + name_ + ")");
    trace_.t.push_back(t);
    trace_.w.push_back(mw * 1e-3);
    last_t_ = t;
}

}  // namespace trn::energy
