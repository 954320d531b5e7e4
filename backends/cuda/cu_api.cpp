// Run-time loading of the CUDA driver library; see cu_api.hpp.
#include "cu_api.hpp"

#include <dlfcn.h>

#include <mutex>
#include <optional>

#include "trn/error.hpp"

namespace trn::cuda {
namespace {

#define TRN_CU_STR(x) TRN_CU_STR2(x)
#define TRN_CU_STR2(x) #x

const char* result_name(CUresult r) {
    switch (r) {
#define TRN_CU_CASE(x) case x: return #x;
        TRN_CU_CASE(CUDA_SUCCESS) TRN_CU_CASE(CUDA_ERROR_INVALID_VALUE) TRN_CU_CASE(CUDA_ERROR_OUT_OF_MEMORY)
        TRN_CU_CASE(CUDA_ERROR_NOT_INITIALIZED) TRN_CU_CASE(CUDA_ERROR_DEINITIALIZED)
        TRN_CU_CASE(CUDA_ERROR_NO_DEVICE) TRN_CU_CASE(CUDA_ERROR_INVALID_DEVICE) TRN_CU_CASE(CUDA_ERROR_DEVICE_NOT_LICENSED)
        TRN_CU_CASE(CUDA_ERROR_INVALID_IMAGE) TRN_CU_CASE(CUDA_ERROR_INVALID_CONTEXT) TRN_CU_CASE(CUDA_ERROR_NO_BINARY_FOR_GPU)
        TRN_CU_CASE(CUDA_ERROR_INVALID_PTX)
        TRN_CU_CASE(CUDA_ERROR_JIT_COMPILER_NOT_FOUND) TRN_CU_CASE(CUDA_ERROR_INVALID_SOURCE) TRN_CU_CASE(CUDA_ERROR_NOT_FOUND)
        TRN_CU_CASE(CUDA_ERROR_ILLEGAL_ADDRESS) TRN_CU_CASE(CUDA_ERROR_LAUNCH_OUT_OF_RESOURCES)
        TRN_CU_CASE(CUDA_ERROR_LAUNCH_TIMEOUT) TRN_CU_CASE(CUDA_ERROR_LAUNCH_FAILED) TRN_CU_CASE(CUDA_ERROR_INVALID_HANDLE)
        TRN_CU_CASE(CUDA_ERROR_SYSTEM_DRIVER_MISMATCH) TRN_CU_CASE(CUDA_ERROR_COMPAT_NOT_SUPPORTED_ON_DEVICE)
        TRN_CU_CASE(CUDA_ERROR_SYSTEM_NOT_READY) TRN_CU_CASE(CUDA_ERROR_OPERATING_SYSTEM) TRN_CU_CASE(CUDA_ERROR_UNKNOWN)
#if CUDA_VERSION >= 11010  // results added in CUDA 11.1
        TRN_CU_CASE(CUDA_ERROR_STUB_LIBRARY) TRN_CU_CASE(CUDA_ERROR_UNSUPPORTED_PTX_VERSION)
#endif
#undef TRN_CU_CASE
        default: return "CUresult (unnamed)";
    }
}

}  // namespace

std::string version_text(int version) { return std::to_string(version / 1000) + "." + std::to_string(version % 1000 / 10); }

std::string result_text(const DriverApi& api, CUresult r) {
    std::string text = std::string(result_name(r)) + " (" + std::to_string(int(r)) + ")";
    const char* what = nullptr;
    if (api.cuGetErrorString && api.cuGetErrorString(r, &what) == CUDA_SUCCESS && what) text += ": " + std::string(what);
    return text;
}

DriverApi open_driver(const std::string& library) {
    void* lib = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char* why = dlerror();
        throw BackendUnavailable("the CUDA driver library " + library + " could not be loaded (" + (why ? why : "unknown reason") +
                                 "): no NVIDIA driver on this machine");
    }
    DriverApi api;
    std::string missing;
#define TRN_CU_LOAD(name)                                                                   \
    api.name = reinterpret_cast<decltype(api.name)>(dlsym(lib, TRN_CU_STR(name)));          \
    if (!api.name) missing += (missing.empty() ? "" : ", ") + std::string(TRN_CU_STR(name));
    TRN_CU_FUNCTIONS(TRN_CU_LOAD)
#undef TRN_CU_LOAD
    if (!missing.empty()) {
        dlclose(lib);
        throw BackendUnavailable(library + " lacks " + missing + ": the NVIDIA driver is older than this build's CUDA " +
                                 version_text(CUDA_VERSION) + " toolkit");
    }
    // The library stays loaded for the life of the process (the driver does not support unloading well).
    if (const CUresult r = api.cuInit(0); r != CUDA_SUCCESS)
        throw BackendUnavailable("cuInit failed: " + result_text(api, r) + " (" + library + ")");
    if (const CUresult r = api.cuDriverGetVersion(&api.driver_version); r != CUDA_SUCCESS)
        throw BackendUnavailable("cuDriverGetVersion failed: " + result_text(api, r));
    // Code built by a CUDA N.x toolkit loads on N.x drivers (minor-version compatibility), not older.
    if (api.driver_version / 1000 < CUDA_VERSION / 1000)
        throw BackendUnavailable("the NVIDIA driver supports CUDA " + version_text(api.driver_version) + ", but this trnkit's " +
                                 "kernels were built with CUDA " + version_text(CUDA_VERSION) + ": update the driver, or build " +
                                 "trnkit with a CUDA " + version_text(api.driver_version) + " toolkit");
    return api;
}

const DriverApi& driver() {
    static std::once_flag once;
    static std::optional<DriverApi> api;
    static std::string why;
    std::call_once(once, [] {
        try {
            api = open_driver("libcuda.so.1");
        } catch (const BackendUnavailable& e) {
            why = e.what();
        }
    });
    if (!api) throw BackendUnavailable(why);
    return *api;
}

void check(CUresult r, const std::string& call) {
    if (r == CUDA_SUCCESS) return;
    std::string msg = "cuda: " + call + " failed: " + result_text(driver(), r);
    if (r == CUDA_ERROR_OUT_OF_MEMORY) msg += "; the device ran out of memory - use a smaller map, template or particle batch";
    throw Error(msg);
}

}  // namespace trn::cuda
