#pragma once
// Finding OpenCL devices and asking them about themselves.
#include <string>
#include <vector>

#include "cl_api.hpp"
#include "trn/backend.hpp"

namespace trn::opencl {

struct DeviceRef {
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
};

// Every device of every platform, in platform order (CPU devices such as PoCL included). When
// there are none, returns an empty list and says why.
std::vector<DeviceRef> enumerate_devices(std::string& why_none);

std::string device_string(cl_device_id device, cl_device_info what);
std::string platform_string(cl_platform_id platform, cl_platform_info what);

template <typename T>
T device_value(cl_device_id device, cl_device_info what) {
    T value{};
    check(clGetDeviceInfo(device, what, sizeof value, &value, nullptr), "clGetDeviceInfo");
    return value;
}

// "opencl:<index>" with the device name, type, platform/driver versions and its limits.
DeviceInfo describe_device(const DeviceRef& ref, int index);

}  // namespace trn::opencl
