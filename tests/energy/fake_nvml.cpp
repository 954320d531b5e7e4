// A stand-in for libnvidia-ml.so.1, built by the tests and dlopen()ed by the NVML sampler through
// its library-path option. One device, "Fake GPU (CPU-driven)", whose board power follows this
// process's CPU use: 10 W idle plus 40 W per busy core, so a bench on the CPU backends sees real
// busy/idle contrast. Its total energy counter is the integral of that power (mJ). Tests that
// need exact values call fake_nvml_control() (found with dlsym in the same library).
// Built a second time with FAKE_NVML_NO_ENERGY: a driver without the energy counter.
#include <time.h>

#include <cstring>

namespace {

constexpr double kIdleW = 10, kPerCoreW = 40;
bool fixed = false;
unsigned fixed_mw = 0;
unsigned long long fixed_mj = 0;
int fail_code = 0;
double t0 = -1, last_wall = -1, last_cpu = 0;

double now(clockid_t c) {
    timespec ts{};
    clock_gettime(c, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

extern "C" {

using nvmlReturn_t = int;
using nvmlDevice_t = void*;
static int the_device;

void fake_nvml_control(int use_fixed, unsigned mw, unsigned long long mj, int fail) {
    fixed = use_fixed != 0, fixed_mw = mw, fixed_mj = mj, fail_code = fail;
}

nvmlReturn_t nvmlInit_v2() {
    if (t0 < 0) t0 = now(CLOCK_MONOTONIC);
    return 0;
}
nvmlReturn_t nvmlShutdown() { return 0; }
const char* nvmlErrorString(nvmlReturn_t r) { return r == 3 ? "Not Supported" : r == 0 ? "Success" : "Fake failure"; }
nvmlReturn_t nvmlDeviceGetCount_v2(unsigned* n) {
    *n = 1;
    return 0;
}
nvmlReturn_t nvmlDeviceGetHandleByIndex_v2(unsigned i, nvmlDevice_t* d) {
    if (i != 0) return 2;  // NVML_ERROR_INVALID_ARGUMENT
    *d = &the_device;
    return 0;
}
nvmlReturn_t nvmlDeviceGetName(nvmlDevice_t, char* name, unsigned len) {
    std::strncpy(name, "Fake GPU (CPU-driven)", len);
    return 0;
}
nvmlReturn_t nvmlDeviceGetPowerUsage(nvmlDevice_t, unsigned* mw) {
    if (fail_code) return fail_code;
    if (fixed) {
        *mw = fixed_mw;
        return 0;
    }
    // Mean power since the previous call: idle plus the CPU cores this process kept busy.
    const double wall = now(CLOCK_MONOTONIC), cpu = now(CLOCK_PROCESS_CPUTIME_ID);
    const double busy = last_wall < 0 || wall <= last_wall ? 0 : (cpu - last_cpu) / (wall - last_wall);
    last_wall = wall, last_cpu = cpu;
    *mw = static_cast<unsigned>(1000 * (kIdleW + kPerCoreW * busy));
    return 0;
}
#ifndef FAKE_NVML_NO_ENERGY
nvmlReturn_t nvmlDeviceGetTotalEnergyConsumption(nvmlDevice_t, unsigned long long* mj) {
    if (fail_code) return fail_code;
    if (fixed) {
        *mj = fixed_mj;
        return 0;
    }
    const double joules = kIdleW * (now(CLOCK_MONOTONIC) - t0) + kPerCoreW * now(CLOCK_PROCESS_CPUTIME_ID);
    *mj = 5000000000ull + static_cast<unsigned long long>(1000 * joules);  // counts since "driver load"
    return 0;
}
#endif
}
