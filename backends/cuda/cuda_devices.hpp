#pragma once
// Finding CUDA devices and asking them about themselves.
#include <string>
#include <vector>

#include "cu_api.hpp"
#include "fatbin_contents.hpp"
#include "trn/backend.hpp"

namespace trn::cuda {

// What the driver reports about one device (cuDeviceGetAttribute and friends).
struct DeviceFacts {
    int ordinal = 0;
    std::string name;
    int arch = 0;  // compute capability, 10 * major + minor
    int multiprocessors = 0, warp_size = 0, max_threads_per_block = 0, max_block_dim_y = 0;
    int max_grid_x = 0, max_grid_y = 0, shared_per_block = 0, clock_khz = 0, memory_clock_khz = 0, bus_bits = 0;
    bool integrated = false;  // shares the host's memory (Jetson)
    std::size_t total_memory = 0;
};

// Every device the driver sees. Throws trn::BackendUnavailable when the driver cannot be used.
std::vector<DeviceFacts> enumerate_devices();

// What this build's fat binaries hold (the NCC and Sobel ones hold the same architectures).
const std::vector<FatbinEntry>& embedded_code();

// "cuda:<index>" with the device, its compute capability, limits and the code it will run.
DeviceInfo describe_device(const DeviceFacts& facts, int driver_version);

}  // namespace trn::cuda
