#pragma once
// The CUDA driver API, opened at run time from libcuda.so.1 (dlopen), so a trnkit built with CUDA
// still starts on a machine without the NVIDIA driver and the cuda family says why it has no
// devices. Every entry point is resolved under the symbol name cuda.h declares it with (cuMemAlloc
// is cuMemAlloc_v2), so the pointer's type is the header's prototype, and no libcuda or libcudart is
// linked. Only this folder includes cuda.h.
#include <cuda.h>

#include <string>

namespace trn::cuda {

#define TRN_CU_FUNCTIONS(X)                                                                                     \
    X(cuInit) X(cuDriverGetVersion) X(cuGetErrorName) X(cuGetErrorString) X(cuDeviceGetCount) X(cuDeviceGet)     \
    X(cuDeviceGetName) X(cuDeviceGetAttribute) X(cuDeviceTotalMem) X(cuDevicePrimaryCtxRetain)                   \
    X(cuDevicePrimaryCtxRelease) X(cuCtxPushCurrent) X(cuCtxPopCurrent) X(cuMemGetInfo) X(cuModuleLoadDataEx)     \
    X(cuModuleUnload) X(cuModuleGetFunction) X(cuFuncGetAttribute) X(cuMemAlloc) X(cuMemFree) X(cuMemcpyHtoDAsync) \
    X(cuMemcpyDtoHAsync) X(cuMemcpyDtoDAsync) X(cuMemcpy2DAsync) X(cuLaunchKernel)            \
    X(cuStreamCreate) X(cuStreamDestroy) X(cuStreamSynchronize) X(cuEventCreate) X(cuEventDestroy)                \
    X(cuEventRecord) X(cuEventSynchronize) X(cuEventElapsedTime)

struct DriverApi {
#define TRN_CU_MEMBER(name) decltype(&::name) name = nullptr;
    TRN_CU_FUNCTIONS(TRN_CU_MEMBER)
#undef TRN_CU_MEMBER
    int driver_version = 0;  // cuDriverGetVersion: 1000 * major + 10 * minor
};

// Opens `library`, resolves every function and calls cuInit(0). Throws trn::BackendUnavailable
// with the reason: the dlopen error, a missing symbol (a driver older than this build's toolkit),
// cuInit's error (no device, a stub library, a driver/kernel-module mismatch) or a driver whose
// CUDA version is below the toolkit's major version (its cubins and PTX would not load).
DriverApi open_driver(const std::string& library);

// The process's driver: open_driver("libcuda.so.1") once; a failure is remembered and rethrown.
const DriverApi& driver();

// "CUDA_ERROR_OUT_OF_MEMORY": the name of a result (our own table first, so a stub or broken
// driver still gives a name), then the driver's text where it has one.
std::string result_text(const DriverApi& api, CUresult r);

// Throws trn::Error "cuda: <call> failed: CUDA_ERROR_... (<n>): <driver text>" unless r is CUDA_SUCCESS.
void check(CUresult r, const std::string& call);

// "13.0" from cuDriverGetVersion's / CUDA_VERSION's 13000.
std::string version_text(int version);

}  // namespace trn::cuda
