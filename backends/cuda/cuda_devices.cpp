// Device enumeration and description for the CUDA family.
#include "cuda_devices.hpp"

#include <sstream>

#include "cuda_build.hpp"
#include "embedded_fatbins.hpp"

namespace trn::cuda {
namespace {

int attribute(const DriverApi& api, CUdevice d, CUdevice_attribute a, const char* name) {
    int v = 0;
    check(api.cuDeviceGetAttribute(&v, a, d), std::string("cuDeviceGetAttribute(") + name + ")");
    return v;
}

DeviceFacts query(const DriverApi& api, int ordinal) {
    CUdevice d = 0;
    check(api.cuDeviceGet(&d, ordinal), "cuDeviceGet(" + std::to_string(ordinal) + ")");
    DeviceFacts f;
    f.ordinal = ordinal;
    char name[256] = {};
    check(api.cuDeviceGetName(name, sizeof name - 1, d), "cuDeviceGetName");
    f.name = name;
#define TRN_CU_ATTR(field, attr) f.field = attribute(api, d, attr, #attr);
    int major = 0, minor = 0;
    major = attribute(api, d, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR, "COMPUTE_CAPABILITY_MAJOR");
    minor = attribute(api, d, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR, "COMPUTE_CAPABILITY_MINOR");
    f.arch = 10 * major + minor;
    TRN_CU_ATTR(multiprocessors, CU_DEVICE_ATTRIBUTE_MULTIPROCESSOR_COUNT)
    TRN_CU_ATTR(warp_size, CU_DEVICE_ATTRIBUTE_WARP_SIZE)
    TRN_CU_ATTR(max_threads_per_block, CU_DEVICE_ATTRIBUTE_MAX_THREADS_PER_BLOCK)
    TRN_CU_ATTR(max_block_dim_y, CU_DEVICE_ATTRIBUTE_MAX_BLOCK_DIM_Y)
    TRN_CU_ATTR(max_grid_x, CU_DEVICE_ATTRIBUTE_MAX_GRID_DIM_X)
    TRN_CU_ATTR(max_grid_y, CU_DEVICE_ATTRIBUTE_MAX_GRID_DIM_Y)
    TRN_CU_ATTR(shared_per_block, CU_DEVICE_ATTRIBUTE_MAX_SHARED_MEMORY_PER_BLOCK)
    TRN_CU_ATTR(clock_khz, CU_DEVICE_ATTRIBUTE_CLOCK_RATE)
    TRN_CU_ATTR(memory_clock_khz, CU_DEVICE_ATTRIBUTE_MEMORY_CLOCK_RATE)
    TRN_CU_ATTR(bus_bits, CU_DEVICE_ATTRIBUTE_GLOBAL_MEMORY_BUS_WIDTH)
#undef TRN_CU_ATTR
    f.integrated = attribute(api, d, CU_DEVICE_ATTRIBUTE_INTEGRATED, "INTEGRATED") != 0;
    check(api.cuDeviceTotalMem(&f.total_memory, d), "cuDeviceTotalMem");
    return f;
}

}  // namespace

std::vector<DeviceFacts> enumerate_devices() {
    const DriverApi& api = driver();
    int count = 0;
    check(api.cuDeviceGetCount(&count), "cuDeviceGetCount");
    std::vector<DeviceFacts> out;
    for (int i = 0; i < count; ++i) out.push_back(query(api, i));
    return out;
}

const std::vector<FatbinEntry>& embedded_code() {
    static const std::vector<FatbinEntry> entries = fatbin_entries(embedded_ncc_score().bytes);
    return entries;
}

DeviceInfo describe_device(const DeviceFacts& f, int driver_version) {
    DeviceInfo info;
    info.name = "cuda:" + std::to_string(f.ordinal);
    info.family = "cuda";
    info.device = f.name;
    info.type = "gpu";
    info.driver = "CUDA driver " + version_text(driver_version) + ", kernels built with CUDA " + build::kToolkitVersion;
    const CodeChoice code = code_for_device(embedded_code(), f.arch);
    std::ostringstream d;
    d << "compute capability " << f.arch / 10 << "." << f.arch % 10 << ", " << f.multiprocessors << " multiprocessors at "
      << f.clock_khz / 1000 << " MHz, " << (f.total_memory >> 20) << " MiB " << (f.integrated ? "memory shared with the host" : "device memory")
      << " (" << f.bus_bits << "-bit, " << f.memory_clock_khz / 1000 << " MHz), " << f.shared_per_block / 1024
      << " KiB shared memory per block, block <= " << f.max_threads_per_block << ", warp " << f.warp_size << "; code: " << code.text;
    info.details = d.str();
    return info;
}

}  // namespace trn::cuda
