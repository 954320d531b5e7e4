// Registers CUDA devices with the backend registry; see cuda_family.hpp.
#include "cuda_family.hpp"

#include "cuda_backend.hpp"
#include "cuda_devices.hpp"

namespace trn {
namespace {

std::vector<DeviceInfo> list_cuda_devices(const BackendOptions&, std::string& why_none) {
    try {
        std::vector<DeviceInfo> out;
        for (const cuda::DeviceFacts& f : cuda::enumerate_devices()) out.push_back(cuda::describe_device(f, cuda::driver().driver_version));
        if (out.empty()) why_none = "the NVIDIA driver reports no CUDA device";
        return out;
    } catch (const Error& e) {  // no driver, cuInit failed, a driver too old for this build
        why_none = e.what();
        return {};
    }
}

}  // namespace

BackendFamily cuda_family() {
    return {"cuda", "CUDA kernels (NVIDIA GPUs and Jetson; the driver libcuda.so.1 is opened at run time)", &list_cuda_devices,
            [](int index, const BackendOptions& options) { return cuda::make_cuda_backend(index, options.cuda); }};
}

}  // namespace trn
