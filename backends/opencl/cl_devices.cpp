// Device enumeration and description for the OpenCL family.
#include "cl_devices.hpp"

#include <sstream>

namespace trn::opencl {
namespace {

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
    return s;
}

std::string mib(cl_ulong bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::vector<DeviceRef> enumerate_devices(std::string& why_none) {
    cl_uint platform_count = 0;
    const cl_int err = clGetPlatformIDs(0, nullptr, &platform_count);
    if (err != CL_SUCCESS || platform_count == 0) {
        why_none = err == CL_SUCCESS || err == -1001
                       ? "no ICD: the OpenCL ICD loader found no driver (no *.icd file in /etc/OpenCL/vendors or in the folder OCL_ICD_VENDORS names)"
                       : std::string("clGetPlatformIDs failed: ") + error_name(err) + " (" + std::to_string(err) + ")";
        return {};
    }
    std::vector<cl_platform_id> platforms(platform_count);
    check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");

    std::vector<DeviceRef> refs;
    std::string problems;
    for (cl_platform_id p : platforms) {
        cl_uint count = 0;
        const cl_int e = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
        if (e == CL_DEVICE_NOT_FOUND || (e == CL_SUCCESS && count == 0)) continue;
        if (e != CL_SUCCESS) {
            problems += "; platform '" + platform_string(p, CL_PLATFORM_NAME) + "': clGetDeviceIDs failed: " + error_name(e);
            continue;
        }
        std::vector<cl_device_id> devices(count);
        check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr), "clGetDeviceIDs");
        for (cl_device_id d : devices) refs.push_back({p, d});
    }
    if (refs.empty()) why_none = std::to_string(platform_count) + " OpenCL platform(s) but no devices" + problems;
    return refs;
}

std::string device_string(cl_device_id device, cl_device_info what) {
    std::size_t size = 0;
    check(clGetDeviceInfo(device, what, 0, nullptr, &size), "clGetDeviceInfo");
    std::string s(size, '\0');
    check(clGetDeviceInfo(device, what, size, s.data(), nullptr), "clGetDeviceInfo");
    return trimmed(s);
}

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
    std::size_t size = 0;
    check(clGetPlatformInfo(platform, what, 0, nullptr, &size), "clGetPlatformInfo");
    std::string s(size, '\0');
    check(clGetPlatformInfo(platform, what, size, s.data(), nullptr), "clGetPlatformInfo");
    return trimmed(s);
}

DeviceInfo describe_device(const DeviceRef& ref, int index) {
    DeviceInfo info;
    info.name = "opencl:" + std::to_string(index);
    info.family = "opencl";
    info.device = device_string(ref.device, CL_DEVICE_NAME);
    const auto type = device_value<cl_device_type>(ref.device, CL_DEVICE_TYPE);
    info.type = (type & CL_DEVICE_TYPE_GPU) ? "gpu" : (type & CL_DEVICE_TYPE_CPU) ? "cpu" : "other";
    info.driver = platform_string(ref.platform, CL_PLATFORM_NAME) + ", " + platform_string(ref.platform, CL_PLATFORM_VERSION) +
                  ", driver " + device_string(ref.device, CL_DRIVER_VERSION);
    std::ostringstream d;
    d << device_value<cl_uint>(ref.device, CL_DEVICE_MAX_COMPUTE_UNITS) << " compute units, "
      << mib(device_value<cl_ulong>(ref.device, CL_DEVICE_GLOBAL_MEM_SIZE)) << " global memory (largest buffer "
      << mib(device_value<cl_ulong>(ref.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE)) << "), "
      << (device_value<cl_ulong>(ref.device, CL_DEVICE_LOCAL_MEM_SIZE) >> 10) << " KiB local memory, work-group <= "
      << device_value<std::size_t>(ref.device, CL_DEVICE_MAX_WORK_GROUP_SIZE) << ", "
      << device_string(ref.device, CL_DEVICE_OPENCL_C_VERSION);
    info.details = d.str();
    return info;
}

}  // namespace trn::opencl
