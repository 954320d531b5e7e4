#pragma once
// Building OpenCL programs, with an on-disk cache of program binaries.
//
// Cache folder: BackendOptions.opencl.program_cache_dir (none when empty; the CLI passes
// $XDG_CACHE_HOME/trnkit/opencl, else ~/.cache/trnkit/opencl, and "" for TRN_OPENCL_CACHE=0). An entry is keyed by the kernel source's SHA-256, the build options, the device
// name and version, the driver version and the platform name and version; the full key is stored
// in the entry and compared on load, so a stale or foreign file is never used. Entries are
// written to a temporary file and renamed into place, so readers never see half a file.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "cl_api.hpp"
#include "trn/backend_options.hpp"
#include "cl_devices.hpp"

namespace trn::opencl {

struct ProgramCacheSettings {
    bool enabled = false;
    std::filesystem::path dir;
};

// From the backend's options (see above).
ProgramCacheSettings program_cache_settings(const BackendOptions::OpenCl& options);

struct BuiltProgram {
    ProgramHandle program;
    bool from_cache = false;  // loaded from a cached binary rather than compiled from source
    double build_ms = 0;      // wall time of creating and building the program
};

// Builds `source` for one device with `options`. With the cache enabled a matching cached binary
// is used when it loads and builds; otherwise the source is compiled and its binary stored. A
// compile failure throws trn::Error naming `file`, the device and the options, with the build log.
BuiltProgram build_program(cl_context context, const DeviceRef& device, std::string_view file, std::string_view source,
                           std::string_view source_sha256, const std::string& options,
                           const ProgramCacheSettings& cache);

// The full cache key and the entry's path for one program on one device.
std::string program_cache_key(const DeviceRef& device, std::string_view source_sha256, const std::string& options);
std::filesystem::path program_cache_path(const ProgramCacheSettings& cache, std::string_view file, const std::string& key);

// Build-time records per device: the backend writes the total program build time of its last
// cold (from source) and warm (from cache) start, so `trnkit devices --verbose` can show both
// without building anything. Returns "" when nothing was recorded yet.
void record_build_time(const ProgramCacheSettings& cache, const DeviceRef& device, bool warm, double ms);
std::string recorded_build_times(const ProgramCacheSettings& cache, const DeviceRef& device);

}  // namespace trn::opencl
